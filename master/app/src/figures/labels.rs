//! Labels that stay readable: a legend or key drawn beside the data rather
//! than over it, and point labels (numbers) placed where they overlap neither
//! each other nor the markers.

use plotters::prelude::*;

/// A figure's drawing area (SVG).
pub type Area<'a> = DrawingArea<SVGBackend<'a>, plotters::coord::Shift>;

/// A drawing error of plotters, boxed.
pub type DrawResult = Result<(), Box<dyn std::error::Error>>;

/// Text size of legends and keys (px).
pub const KEY_FONT: u32 = 13;
/// Height of a legend or key row (px).
pub const KEY_ROW: i32 = 17;
/// Width of a character of the keys' font, for layout (px).
pub const CHAR_WIDTH: i32 = 7;

/// One legend entry: a line (or a marker) in a colour, and its text.
pub struct Entry {
    /// The entry's text.
    pub text: String,
    /// Its colour.
    pub colour: RGBAColor,
    /// A marker rather than a line.
    pub marker: bool,
}

impl Entry {
    /// One entry per name in its colour (with a marker or a line).
    pub fn each(names: &[String], colours: &[RGBAColor], marker: bool) -> Vec<Entry> {
        let entry = |(text, colour): (&String, &RGBAColor)| Entry {
            text: text.clone(),
            colour: *colour,
            marker,
        };
        names.iter().zip(colours).map(entry).collect()
    }
}

/// Draws `entries` one per row from the top left of `area` (a column beside
/// the chart), under an optional heading.
pub fn side_legend(area: &Area<'_>, heading: &str, entries: &[Entry]) -> DrawResult {
    let mut y = 30;
    if !heading.is_empty() {
        area.draw(&Text::new(
            heading.to_owned(),
            (8, y),
            ("sans-serif", KEY_FONT).into_font().style(FontStyle::Bold),
        ))?;
        y += KEY_ROW;
    }
    for e in entries {
        let middle = y + KEY_ROW / 2 - 2;
        if e.marker {
            area.draw(&Circle::new((18, middle), 4, e.colour.filled()))?;
        } else {
            area.draw(&PathElement::new(
                vec![(8, middle), (30, middle)],
                e.colour.stroke_width(2),
            ))?;
        }
        area.draw(&Text::new(
            e.text.clone(),
            (36, y),
            ("sans-serif", KEY_FONT),
        ))?;
        y += KEY_ROW;
    }
    Ok(())
}

/// A pixel box: left, top, right, bottom.
type PixelBox = (i32, i32, i32, i32);

fn overlap(a: PixelBox, b: PixelBox) -> bool {
    a.0 < b.2 && b.0 < a.2 && a.1 < b.3 && b.1 < a.3
}

/// Where to write each point's label (the top left of its text), given the
/// points' pixels, the labels' lengths in characters and the plot's pixel
/// bounds: the first of a ring of places around the point that overlaps no
/// label placed before and no marker and stays inside; failing all, the
/// first place inside.
pub fn place_labels(points: &[(i32, i32)], lengths: &[usize], bounds: PixelBox) -> Vec<(i32, i32)> {
    let height = 12;
    let markers: Vec<PixelBox> = points
        .iter()
        .map(|&(x, y)| (x - 5, y - 5, x + 5, y + 5))
        .collect();
    let mut placed: Vec<PixelBox> = Vec::with_capacity(points.len());
    let mut corners = Vec::with_capacity(points.len());
    for (&(x, y), &length) in points.iter().zip(lengths) {
        let width = CHAR_WIDTH * length as i32;
        let ring = [
            (7, -height - 3),
            (7, 3),
            (-7 - width, -height - 3),
            (-7 - width, 3),
            (-width / 2, -height - 8),
            (-width / 2, 8),
            (12, -height / 2),
            (-12 - width, -height / 2),
            (7, -2 * height - 6),
            (7, height + 6),
            (-7 - width, -2 * height - 6),
            (-7 - width, height + 6),
        ];
        let boxes = ring.map(|(dx, dy)| (x + dx, y + dy, x + dx + width, y + dy + height));
        let inside =
            |b: &PixelBox| b.0 >= bounds.0 && b.1 >= bounds.1 && b.2 <= bounds.2 && b.3 <= bounds.3;
        let free = |b: &PixelBox| !placed.iter().chain(&markers).any(|p| overlap(*b, *p));
        let chosen = (boxes.iter().find(|b| inside(b) && free(b)))
            .or_else(|| boxes.iter().find(|b| inside(b)))
            .copied()
            .unwrap_or(boxes[0]);
        placed.push(chosen);
        corners.push((chosen.0, chosen.1));
    }
    corners
}

/// The series' own legend (their `label`s) inside the chart, on a white box
/// with a black border: for charts whose lines leave a corner free.
pub fn inner_legend<'a, DB: DrawingBackend + 'a, CT: plotters::coord::CoordTranslate>(
    chart: &mut ChartContext<'a, DB, CT>,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_of_crowded_points_do_not_overlap() {
        let points: Vec<(i32, i32)> = (0..8).map(|i| (300 + 3 * i, 200 + 2 * i)).collect();
        let lengths = vec![2; 8];
        let corners = place_labels(&points, &lengths, (0, 0, 600, 400));
        let boxes: Vec<PixelBox> = corners
            .iter()
            .map(|&(x, y)| (x, y, x + 2 * CHAR_WIDTH, y + 12))
            .collect();
        for (i, a) in boxes.iter().enumerate() {
            for b in &boxes[i + 1..] {
                assert!(!overlap(*a, *b), "{a:?} overlaps {b:?}");
            }
            assert!(a.0 >= 0 && a.2 <= 600 && a.1 >= 0 && a.3 <= 400);
        }
    }
}
