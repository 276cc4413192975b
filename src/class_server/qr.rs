//! The students' link as a QR code: rows of modules (`#` dark, ` ` light, no quiet zone) as the
//! welcome message carries them for any client to draw, and the same drawn in a terminal with
//! half-block characters and a quiet zone.

/// The light margin a reader needs around the code, in modules.
const QUIET_ZONE: usize = 4;

/// `text` as a QR code: one string per row of modules, `#` dark and ` ` light, without a quiet
/// zone; empty if `text` is too long for a QR code (more than about 2900 bytes).
///
/// # Examples
///
/// ```
/// use armlab::class_server::qr::qr_rows;
///
/// let rows = qr_rows("http://127.0.0.1:8737/?code=K7QX2M");
/// // A square of an odd width (21, 25, 29, ... modules), its corners dark (the finder
/// // patterns).
/// assert!(rows.len() >= 21 && rows.len() % 2 == 1);
/// assert!(rows.iter().all(|r| r.chars().count() == rows.len()));
/// assert!(rows[0].starts_with("#######") && rows[0].ends_with("#######"));
/// ```
pub fn qr_rows(text: &str) -> Vec<String> {
    let Ok(code) = qrcode::QrCode::new(text.as_bytes()) else {
        return Vec::new();
    };
    let width = code.width();
    code.to_colors()
        .chunks(width)
        .map(|row| {
            row.iter()
                .map(|c| match c {
                    qrcode::Color::Dark => '#',
                    qrcode::Color::Light => ' ',
                })
                .collect()
        })
        .collect()
}

/// Rows of [`qr_rows`] drawn for a terminal: two rows of modules per line with half blocks
/// (`▀`, `▄`, `█`), a quiet zone of four modules around. The light modules and the quiet zone
/// are drawn and the dark ones left blank, as for a terminal with light text on a dark
/// background (phone cameras also read the code the other way round).
///
/// # Examples
///
/// ```
/// use armlab::class_server::qr::{qr_rows, terminal};
///
/// let rows = qr_rows("http://127.0.0.1:8737/?code=K7QX2M");
/// let drawn = terminal(&rows);
/// let lines: Vec<&str> = drawn.lines().collect();
/// // Two rows of modules a line, the quiet zone's eight modules included.
/// assert_eq!(lines.len(), (rows.len() + 8).div_ceil(2));
/// assert!(lines.iter().all(|l| l.chars().count() == rows.len() + 8));
/// // The first line is all quiet zone: light above and below.
/// assert!(lines[0].chars().all(|c| c == '█'));
/// ```
pub fn terminal(rows: &[String]) -> String {
    if rows.is_empty() {
        return String::new();
    }
    let width = rows.iter().map(|r| r.chars().count()).max().unwrap_or(0);
    let side = width + 2 * QUIET_ZONE;
    let height = rows.len() + 2 * QUIET_ZONE;
    // Light (drawn) at (x, y) of the code with its quiet zone.
    let light = |x: usize, y: usize| -> bool {
        if x < QUIET_ZONE || y < QUIET_ZONE || y >= rows.len() + QUIET_ZONE {
            return true;
        }
        rows[y - QUIET_ZONE].chars().nth(x - QUIET_ZONE) != Some('#')
    };
    let mut out = String::new();
    for y in (0..height).step_by(2) {
        for x in 0..side {
            let top = light(x, y);
            let bottom = y + 1 >= height || light(x, y + 1);
            out.push(match (top, bottom) {
                (true, true) => '█',
                (true, false) => '▀',
                (false, true) => '▄',
                (false, false) => ' ',
            });
        }
        out.push('\n');
    }
    out
}
