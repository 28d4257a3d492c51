//! The page: the HTML template with the title, the data and the script put in. The template has
//! three markers, each exactly once: `{{TITLE}}` (text), `{{DATA}}` (inside
//! `<script type="application/json">`) and `{{SCRIPT}}` (inside `<script>`). They are replaced in
//! one pass over the template, so text inside the data or the script is never taken for one.

/// The template or script cannot make a page.
#[derive(Debug, thiserror::Error)]
pub enum PageError {
    #[error("the viewer template lacks the marker {0} (or has it more than once)")]
    Marker(&'static str),
}

const MARKERS: [&str; 3] = ["{{TITLE}}", "{{DATA}}", "{{SCRIPT}}"];

/// Makes the page. `data_json` must already be safe inside a script element
/// ([`super::ViewerDoc::to_json`] is); the script gets its `</script` escaped here.
pub fn viewer_page(template: &str, title: &str, data_json: &str, script: &str) -> Result<String, PageError> {
    let title = html_escape(title);
    let script = script.replace("</script", "<\\/script");
    let mut found: Vec<(usize, &'static str)> = Vec::new();
    for marker in MARKERS {
        let mut hits = template.match_indices(marker);
        match (hits.next(), hits.next()) {
            (Some((at, _)), None) => found.push((at, marker)),
            _ => return Err(PageError::Marker(marker)),
        }
    }
    found.sort();
    let mut page = String::with_capacity(template.len() + data_json.len() + script.len());
    let mut rest = 0;
    for (at, marker) in found {
        page.push_str(&template[rest..at]);
        page.push_str(match marker {
            "{{TITLE}}" => &title,
            "{{DATA}}" => data_json,
            _ => &script,
        });
        rest = at + marker.len();
    }
    page.push_str(&template[rest..]);
    Ok(page)
}

fn html_escape(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markers_are_replaced_once_and_contents_left_alone() {
        let template = "<title>{{TITLE}}</title><script id=d>{{DATA}}</script><script>{{SCRIPT}}</script>";
        let page = viewer_page(template, "a<b", "{\"x\":\"{{SCRIPT}}\"}", "let s='</script>';").unwrap();
        assert_eq!(
            page,
            "<title>a&lt;b</title><script id=d>{\"x\":\"{{SCRIPT}}\"}</script><script>let s='<\\/script>';</script>"
        );
    }

    #[test]
    fn a_missing_marker_is_an_error() {
        assert!(matches!(viewer_page("{{TITLE}}{{DATA}}", "", "", ""), Err(PageError::Marker("{{SCRIPT}}"))));
    }
}
