//! Estimates not to be trusted: a parameter the measurements cannot identify on its own (at the
//! nominal parameters or at the estimate), or whose standard deviation exceeds its own size.
//! The app's table marks them red with the reason, and a model saved with them carries the
//! reasons in its header.

use super::CalibrationReport;
use super::model::Kind;
use std::fmt;

/// Why an estimate is doubtful.
#[derive(Debug, Clone, PartialEq)]
pub enum Doubt {
    /// The measurements cannot identify the parameter on its own.
    Unidentifiable {
        /// What the data see instead, in words ("d2 and d3 only as d2 + d3 (axes 2 and 3 are
        /// parallel)"); empty when no combination names it.
        combination: String,
    },
    /// The standard deviation exceeds the estimate's own size (or, for an estimate near zero,
    /// 1 mm, 1 mrad or 1 urad/Nm).
    Uncertain {
        /// The standard deviation (m, rad or rad/Nm).
        std: f64,
    },
}

/// One doubtful estimate.
#[derive(Debug, Clone, PartialEq)]
pub struct DoubtfulParameter {
    /// Its index in zeta.
    pub index: usize,
    /// Its name ("d2").
    pub name: String,
    /// Its kind (for the unit).
    pub kind: Kind,
    /// The estimate (m, rad or rad/Nm).
    pub estimate: f64,
    /// Why.
    pub doubt: Doubt,
}

impl DoubtfulParameter {
    /// The reason alone, in words ("not identifiable: d2 and d3 only as d2 + d3 ...",
    /// "std 4.1e3 mm exceeds the estimate").
    pub fn reason(&self) -> String {
        let (scale, unit) = self.kind.display();
        match &self.doubt {
            Doubt::Unidentifiable { combination } if combination.is_empty() => {
                "not identifiable by these measurements".into()
            }
            Doubt::Unidentifiable { combination } => format!("not identifiable: {combination}"),
            Doubt::Uncertain { std } => {
                format!("std {:.2e} {unit} exceeds the estimate itself", std * scale)
            }
        }
    }
}

impl fmt::Display for DoubtfulParameter {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (scale, unit) = self.kind.display();
        write!(
            f,
            "{} = {:.4} {unit}: {}",
            self.name,
            self.estimate * scale,
            self.reason()
        )
    }
}

/// The size below which an estimate counts as zero when its std is compared with it.
pub fn floor(kind: Kind) -> f64 {
    match kind {
        Kind::Compliance => 1e-6,
        _ => 1e-3,
    }
}

/// The doubtful estimates of `report`, in the order of zeta. A parameter kept nominal or fixed
/// is never doubtful (it was not estimated).
pub fn doubtful_parameters(report: &CalibrationReport) -> Vec<DoubtfulParameter> {
    let combinations: Vec<&String> = report
        .nominal
        .combinations
        .iter()
        .chain(&report.at_estimate.combinations)
        .collect();
    let naming = |name: &str| {
        combinations
            .iter()
            .find(|c| c.split(|ch: char| !ch.is_alphanumeric()).any(|w| w == name))
            .map_or(String::new(), |c| (*c).clone())
    };
    let mut out = Vec::new();
    for (k, p) in report.parameters.iter().enumerate() {
        let kept = report.auto_fixed.iter().any(|(n, _)| *n == p.name);
        if kept || p.fixed {
            continue;
        }
        let flag = |i: &super::Identifiability| i.identifiable.get(k) == Some(&false);
        let estimate = report.estimate[k];
        let doubt = if flag(&report.nominal) || flag(&report.at_estimate) {
            Doubt::Unidentifiable {
                combination: naming(&p.name),
            }
        } else {
            match report.std[k] {
                Some(std) if std > estimate.abs().max(floor(p.kind)) => Doubt::Uncertain { std },
                _ => continue,
            }
        };
        out.push(DoubtfulParameter {
            index: k,
            name: p.name.clone(),
            kind: p.kind,
            estimate,
            doubt,
        });
    }
    out
}

/// The header a model saved with doubtful estimates carries: `# ` comment lines for a TOML
/// model file, an XML comment for a URDF (`xml`); empty when there is no doubt.
pub fn doubt_header(doubts: &[DoubtfulParameter], xml: bool) -> String {
    if doubts.is_empty() {
        return String::new();
    }
    let title = "WARNING: these estimates are not to be trusted (saved anyway, after a warning):";
    let lines: Vec<String> = doubts.iter().map(|d| format!("  {d}")).collect();
    if xml {
        let body = lines.join("\n").replace("--", "- -");
        format!("<!-- {title}\n{body}\n-->\n")
    } else {
        let mut s = format!("# {title}\n");
        for l in lines {
            s.push_str(&format!("# {l}\n"));
        }
        s
    }
}
