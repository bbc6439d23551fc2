//! Tooltips on an SVG figure's points: a transparent circle with a `<title>`
//! over each point, added before the figure's closing tag, so a browser shows
//! the run's settings when the pointer rests on it (no script needed).

use super::escape;
use std::fmt::Write as _;

/// A point of a figure in its pixels, and what hovering on it shows.
#[derive(Clone, Debug)]
pub struct Point {
    /// x in the SVG's pixels.
    pub x: i32,
    /// y in the SVG's pixels.
    pub y: i32,
    /// What the point shows.
    pub text: String,
}

/// The SVG with a hover circle per point (radius 8 px).
pub fn with_tooltips(svg: &str, points: &[Point]) -> String {
    let Some(end) = svg.rfind("</svg>") else {
        return svg.to_owned();
    };
    let mut layer = String::from("<g class=\"hover\">");
    for p in points {
        let _ = write!(
            layer,
            "<circle cx=\"{}\" cy=\"{}\" r=\"8\" fill=\"transparent\" stroke=\"none\"><title>{}</title></circle>",
            p.x,
            p.y,
            escape(&p.text)
        );
    }
    layer += "</g>\n";
    format!("{}{layer}{}", &svg[..end], &svg[end..])
}
