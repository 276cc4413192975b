//! MoveIt's SRDF `<disable_collisions>` elements: read into the allowed-collision matrix, and
//! written from it.

use super::CollisionError;
use super::matrix::{AllowedCollisions, PairReason};
use std::path::Path;

/// Reads the `<disable_collisions link1="..." link2="..." reason="..."/>` elements of SRDF
/// text (the rest of the file is ignored). `link_names` are the robot's links: a pair naming
/// another link is an error naming the line.
pub fn parse_srdf(
    text: &str,
    path: &Path,
    link_names: &[&str],
) -> Result<Vec<(String, String, PairReason)>, CollisionError> {
    let err = |line: usize, problem: String| CollisionError::Srdf {
        path: path.to_path_buf(),
        line,
        problem,
    };
    let doc =
        roxmltree::Document::parse(text).map_err(|e| err(e.pos().row as usize, e.to_string()))?;
    let mut out = Vec::new();
    for node in doc
        .descendants()
        .filter(|n| n.has_tag_name("disable_collisions"))
    {
        let line = doc.text_pos_at(node.range().start).row as usize;
        let attr = |name: &str| {
            node.attribute(name)
                .ok_or_else(|| err(line, format!("<disable_collisions> has no `{name}`")))
        };
        let (a, b) = (attr("link1")?, attr("link2")?);
        for l in [a, b] {
            if !link_names.contains(&l) {
                return Err(err(
                    line,
                    format!(
                        "<disable_collisions> names link \"{l}\", which the robot does not have"
                    ),
                ));
            }
        }
        let reason = PairReason::from_word(node.attribute("reason").unwrap_or("User"));
        out.push((a.to_string(), b.to_string(), reason));
    }
    Ok(out)
}

/// An SRDF holding the matrix's disabled pairs, for `robot_name`.
pub fn write_srdf(matrix: &AllowedCollisions, robot_name: &str) -> String {
    let escape = |s: &str| {
        s.replace('&', "&amp;")
            .replace('"', "&quot;")
            .replace('<', "&lt;")
            .replace('>', "&gt;")
    };
    let mut out = format!(
        "<?xml version=\"1.0\" ?>\n<!-- Written by armlab: the allowed-collision matrix, \
         sampled as MoveIt's Setup Assistant does. -->\n<robot name=\"{}\">\n",
        escape(robot_name)
    );
    for p in matrix.disabled() {
        out += &format!(
            "    <disable_collisions link1=\"{}\" link2=\"{}\" reason=\"{}\" />\n",
            escape(&p.a),
            escape(&p.b),
            p.reason.as_str()
        );
    }
    out += "</robot>\n";
    out
}
