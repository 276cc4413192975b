//! Markdown text as the reader should see it: an exercise sheet's question (its tables of joint
//! axes and DH rows, headings, a matrix's rows) and a lesson step's caption. Rendered by
//! egui_commonmark (CommonMark via pulldown-cmark) at a chosen body size, so that a sheet reads
//! as large on a projector as the rest of the window; a heading is a step larger.
//!
//! Images are not loaded (no image loader is installed: a sheet or lesson never needs one) and
//! raw HTML is shown as text, never interpreted. A code block (a sheet's matrix rows) is shown as
//! lines of monospaced text, its spaces kept: egui_commonmark draws a code block with a copy
//! button whose icon (U+1F5D0) no font of the app has.

use egui_commonmark::{CommonMarkCache, CommonMarkViewer};
use pulldown_cmark::{Event, Parser, Tag, TagEnd};
use std::borrow::Cow;

/// What the renderer keeps between frames for one place that shows Markdown: egui_commonmark's
/// cache, and the last text with its code blocks rewritten (made again only when it changes).
#[derive(Default)]
pub struct MarkdownCache {
    viewer: CommonMarkCache,
    source: String,
    shown: String,
}

/// A copy starts with an empty cache: it holds only layout worked out from the text.
impl Clone for MarkdownCache {
    fn clone(&self) -> Self {
        Self::default()
    }
}

impl std::fmt::Debug for MarkdownCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("MarkdownCache")
    }
}

/// Renders `text` as Markdown at body size `size` (points).
pub fn show(ui: &mut egui::Ui, cache: &mut MarkdownCache, text: &str, size: f32) {
    ui.scope(|ui| {
        let styles = &mut ui.style_mut().text_styles;
        for (style, scale) in [
            (egui::TextStyle::Body, 1.0),
            (egui::TextStyle::Button, 1.0),
            (egui::TextStyle::Monospace, 0.95),
            (egui::TextStyle::Small, 0.8),
            (egui::TextStyle::Heading, 1.3),
        ] {
            if let Some(font) = styles.get_mut(&style) {
                font.size = size * scale;
            }
        }
        if cache.source != text {
            cache.shown = without_code_blocks(text).into_owned();
            cache.source = text.to_string();
        }
        CommonMarkViewer::new().show(ui, &mut cache.viewer, &cache.shown);
    });
}

/// `text` with each top-level code block written as a paragraph of inline-code lines joined by
/// hard line breaks, its spaces as no-break spaces (so that a matrix's columns stay aligned).
/// A text without code blocks comes back as it is.
pub fn without_code_blocks(text: &str) -> Cow<'_, str> {
    let mut out = String::new();
    let (mut copied_to, mut block_start, mut code) = (0, None, String::new());
    for (event, range) in Parser::new(text).into_offset_iter() {
        match event {
            Event::Start(Tag::CodeBlock(_)) => {
                // from the start of its first line (an indented block's range skips the indent)
                let line_start = text[..range.start].rfind('\n').map_or(0, |i| i + 1);
                block_start = Some(line_start.max(copied_to));
                code.clear();
            }
            Event::Text(t) if block_start.is_some() => code.push_str(&t),
            Event::End(TagEnd::CodeBlock) => {
                let Some(start) = block_start.take() else {
                    continue;
                };
                out.push_str(&text[copied_to..start]);
                out.push_str(&inline_lines(&code));
                // a blank line after it, so that the next line starts a paragraph of its own
                out.push('\n');
                if !text[range.end..].starts_with('\n') {
                    out.push('\n');
                }
                copied_to = range.end;
            }
            _ => {}
        }
    }
    if copied_to == 0 {
        return Cow::Borrowed(text);
    }
    out.push_str(&text[copied_to..]);
    Cow::Owned(out)
}

/// `code`'s lines as inline code spans joined by hard line breaks (a backslash at a line's end).
fn inline_lines(code: &str) -> String {
    code.trim_end_matches('\n')
        .lines()
        .map(|line| {
            let kept = line.replace(' ', "\u{a0}");
            if kept.is_empty() {
                return "\u{a0}".to_string();
            }
            // a fence longer than any run of backticks in the line, and a space inside it where
            // the line starts or ends with one (CommonMark's rule for code spans)
            let longest = kept.split(|c| c != '`').map(str::len).max().unwrap_or(0);
            let fence = "`".repeat(longest + 1);
            let pad = if kept.starts_with('`') || kept.ends_with('`') {
                " "
            } else {
                ""
            };
            format!("{fence}{pad}{kept}{pad}{fence}")
        })
        .collect::<Vec<_>>()
        .join("\\\n")
}
