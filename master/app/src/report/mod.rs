//! One self-contained HTML page per run and per study (`report.html`, issue
//! 28): the command that made it, the tables, and the figures inline (SVG, so
//! nothing is fetched: no network, no script library); the points of an
//! error-against-cost figure carry the run's settings as a tooltip
//! ([`hover`]). Its one script sorts a table by a column when its header is
//! clicked.

pub mod hover;
mod markdown;
pub mod run_page;

use std::fmt::Write as _;
use std::path::Path;

/// A part of a report page.
pub enum Part {
    /// A second-level heading.
    Heading(String),
    /// Markdown as the study commands write it: pipe tables and paragraphs.
    Markdown(String),
    /// An SVG figure, read from its file, with its hover points.
    Figure {
        /// The SVG text.
        svg: String,
        /// Points that show a value when hovered.
        hover: Vec<hover::Point>,
    },
}

impl Part {
    /// A figure from its file; missing or unreadable, a line saying so.
    pub fn figure(path: &Path, hover: Vec<hover::Point>) -> Part {
        match std::fs::read_to_string(path) {
            Ok(svg) => Part::Figure { svg, hover },
            Err(e) => Part::Markdown(format!("(figure {} not readable: {e})", path.display())),
        }
    }
}

const STYLE: &str = "body{font-family:sans-serif;margin:2em;max-width:1400px}\
table{border-collapse:collapse;font-size:13px;margin:1em 0}\
th,td{border:1px solid #bbb;padding:3px 6px;text-align:right}\
th{background:#eee;cursor:pointer}td:first-child,th:first-child{text-align:left}\
code{background:#f4f4f4;padding:2px 4px}figure{margin:1em 0}svg{max-width:100%;height:auto}";

/// Sorts a table by the clicked column (numbers as numbers).
const SCRIPT: &str = "document.querySelectorAll('th').forEach(function(th){th.addEventListener('click',function(){\
var table=th.closest('table');var body=table.tBodies[0];var k=Array.prototype.indexOf.call(th.parentNode.children,th);\
var rows=Array.prototype.slice.call(body.rows);var up=th.dataset.up!=='1';th.dataset.up=up?'1':'0';\
rows.sort(function(a,b){var x=a.cells[k].textContent,y=b.cells[k].textContent;var p=parseFloat(x),q=parseFloat(y);\
var c=(isNaN(p)||isNaN(q))?x.localeCompare(y):p-q;return up?c:-c;});rows.forEach(function(r){body.appendChild(r);});});});";

/// The page's HTML.
pub fn page(title: &str, command: &str, parts: &[Part]) -> String {
    let mut html = String::new();
    let _ = write!(
        html,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{t}</title><style>{STYLE}</style></head><body>\n<h1>{t}</h1>\n<p>Made by <code>{c}</code></p>\n",
        t = escape(title),
        c = escape(command)
    );
    for part in parts {
        match part {
            Part::Heading(text) => {
                let _ = writeln!(html, "<h2>{}</h2>", escape(text));
            }
            Part::Markdown(text) => html += &markdown::to_html(text),
            Part::Figure { svg, hover } => {
                let _ = writeln!(
                    html,
                    "<figure>{}</figure>",
                    hover::with_tooltips(svg, hover)
                );
            }
        }
    }
    let _ = write!(html, "<script>{SCRIPT}</script>\n</body></html>\n");
    html
}

/// The command line that is running, for the page.
pub fn command_line() -> String {
    let mut args = std::env::args();
    let program = args.next().map(|p| {
        Path::new(&p)
            .file_name()
            .map_or(p.clone(), |n| n.to_string_lossy().into_owned())
    });
    program
        .into_iter()
        .chain(args)
        .collect::<Vec<_>>()
        .join(" ")
}

/// Text made safe for HTML.
pub fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
