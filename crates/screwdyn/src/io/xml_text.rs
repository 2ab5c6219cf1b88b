//! Text inside the XML the exporters write (URDF, MJCF): attribute values and comments.

/// `s` as the text of a double-quoted XML attribute: markup characters as entities, and tab,
/// newline and carriage return as character references (an XML reader turns them into spaces
/// otherwise).
pub(crate) fn xml_escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\t' => out.push_str("&#9;"),
            '\n' => out.push_str("&#10;"),
            '\r' => out.push_str("&#13;"),
            c => out.push(c),
        }
    }
    out
}

/// `s` as text inside an XML comment, which ends at the first `--` and knows no entities:
/// every `-` after a `-` is preceded by a space, and line breaks become spaces.
pub(crate) fn xml_comment(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        if c == '-' && out.ends_with('-') {
            out.push(' ');
        }
        out.push(if c.is_control() { ' ' } else { c });
    }
    out
}
