//! The study commands' Markdown (pipe tables, paragraphs) as HTML: a run of
//! lines starting with `|` is a table (its second line the separator), any
//! other block of lines a paragraph.

use super::escape;

/// Markdown text as HTML.
pub(super) fn to_html(text: &str) -> String {
    let mut html = String::new();
    let mut lines = text.lines().peekable();
    while let Some(line) = lines.next() {
        if line.trim().is_empty() {
            continue;
        }
        if line.starts_with('|') {
            let mut rows = vec![line];
            while let Some(next) = lines.next_if(|l| l.starts_with('|')) {
                rows.push(next);
            }
            html += &table(&rows);
        } else {
            let mut block = vec![line];
            while let Some(next) = lines.next_if(|l| !l.trim().is_empty() && !l.starts_with('|')) {
                block.push(next);
            }
            html += &format!("<p>{}</p>\n", inline(&block.join(" ")));
        }
    }
    html
}

/// A pipe table: header, separator, body.
fn table(rows: &[&str]) -> String {
    let cells = |row: &str| -> Vec<String> {
        let inner = row.trim().trim_start_matches('|').trim_end_matches('|');
        inner.split('|').map(|c| inline(c.trim())).collect()
    };
    let mut html = String::from("<table>\n<thead><tr>");
    for c in cells(rows[0]) {
        html += &format!("<th>{c}</th>");
    }
    html += "</tr></thead>\n<tbody>\n";
    for row in rows
        .iter()
        .skip(1)
        .filter(|r| !r.starts_with("|---") && !r.starts_with("| ---"))
    {
        html += "<tr>";
        for c in cells(row) {
            html += &format!("<td>{c}</td>");
        }
        html += "</tr>\n";
    }
    html + "</tbody></table>\n"
}

/// Inline text: escaped, `code` spans kept as code.
fn inline(text: &str) -> String {
    let escaped = escape(text);
    let mut out = String::new();
    for (i, piece) in escaped.split('`').enumerate() {
        if i % 2 == 1 {
            out += &format!("<code>{piece}</code>");
        } else {
            out += piece;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_and_paragraphs_become_html() {
        let md =
            "Study of `b3`: <errors>.\n\n| a | b |\n|---|---|\n| 1 | x<y |\n| 2 | z |\n\nDone.";
        let html = to_html(md);
        assert!(
            html.contains("<p>Study of <code>b3</code>: &lt;errors&gt;.</p>"),
            "{html}"
        );
        assert!(
            html.contains("<thead><tr><th>a</th><th>b</th></tr></thead>"),
            "{html}"
        );
        assert!(
            html.contains("<tr><td>1</td><td>x&lt;y</td></tr>"),
            "{html}"
        );
        assert_eq!(html.matches("<tr>").count(), 3);
        assert!(html.ends_with("<p>Done.</p>\n"));
    }
}
