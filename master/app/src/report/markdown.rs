//! The study commands' Markdown as HTML, by pulldown-cmark (CommonMark with
//! pipe tables): headings, emphasis, lists, code and tables. Anything that
//! looks like HTML in it (`<errors>`, `x<y`) is shown as text: the reports
//! write no markup of their own through Markdown.

use pulldown_cmark::{Event, Options, Parser, html};

/// Markdown text as HTML.
pub(super) fn to_html(text: &str) -> String {
    let events = Parser::new_ext(text, Options::ENABLE_TABLES).map(|event| match event {
        Event::Html(raw) | Event::InlineHtml(raw) => Event::Text(raw),
        other => other,
    });
    let mut out = String::new();
    html::push_html(&mut out, events);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_paragraphs_headings_and_emphasis_become_html() {
        let md = "## phi1\n\nStudy of `b3`: <errors>.\n\n| a | b |\n|---|---|\n| 1 | x<y |\n| 2 | z |\n\n**Caution:** done.";
        let html = to_html(md);
        assert!(html.contains("<h2>phi1</h2>"), "{html}");
        assert!(
            html.contains("<p>Study of <code>b3</code>: &lt;errors&gt;.</p>"),
            "{html}"
        );
        assert!(html.contains("<th>a</th><th>b</th>"), "{html}");
        assert!(html.contains("<td>1</td><td>x&lt;y</td>"), "{html}");
        assert_eq!(html.matches("<tr>").count(), 3, "{html}");
        assert!(html.contains("<strong>Caution:</strong> done."), "{html}");
        assert!(!html.contains("**") && !html.contains("##"), "{html}");
    }
}
