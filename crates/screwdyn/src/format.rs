//! Numbers and names as they are written to CSV and JSON output files: the shortest decimal
//! text that reads back to the same `f64` (Ryū), `NaN` / `inf` / `-inf` in CSV, `null` in
//! JSON (which has no non-finite numbers), and CSV fields quoted where needed.
//!
//! ```
//! use screwdyn::format::NumberText;
//! let mut text = NumberText::new();
//! assert_eq!(text.csv(0.1), "0.1");
//! assert_eq!(text.csv(f64::NEG_INFINITY), "-inf");
//! assert_eq!(text.json(f64::NAN), "null");
//! assert_eq!(text.json(2.0), "2.0");
//! ```

use std::borrow::Cow;

/// A reusable buffer that turns `f64`s into text without allocating.
#[derive(Default)]
pub struct NumberText {
    buffer: ryu::Buffer,
}

impl std::fmt::Debug for NumberText {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("NumberText")
    }
}

impl NumberText {
    /// A new buffer.
    pub fn new() -> Self {
        NumberText::default()
    }

    /// `x` for a CSV cell: the shortest text that reads back to `x`, or `NaN`, `inf`, `-inf`
    /// (what Rust's and NumPy's parsers read back).
    pub fn csv(&mut self, x: f64) -> &str {
        if x.is_finite() {
            self.buffer.format_finite(x)
        } else if x.is_nan() {
            "NaN"
        } else if x > 0.0 {
            "inf"
        } else {
            "-inf"
        }
    }

    /// `x` as a JSON value: the shortest text that reads back to `x`, or `null` for NaN and
    /// infinities.
    pub fn json(&mut self, x: f64) -> &str {
        if x.is_finite() {
            self.buffer.format_finite(x)
        } else {
            "null"
        }
    }
}

/// `x` as a [`serde_json::Value`]: a number, or `null` for NaN and infinities (the value whose
/// text is [`NumberText::json`]).
///
/// ```
/// assert_eq!(screwdyn::format::json_number(1.5), serde_json::json!(1.5));
/// assert!(screwdyn::format::json_number(f64::INFINITY).is_null());
/// ```
pub fn json_number(x: f64) -> serde_json::Value {
    serde_json::Number::from_f64(x).map_or(serde_json::Value::Null, serde_json::Value::Number)
}

/// `name` as a CSV field: quoted (with `"` doubled) when it holds a comma, quote or line break.
///
/// ```
/// use screwdyn::format::csv_field;
/// assert_eq!(csv_field("q.j1"), "q.j1");
/// assert_eq!(csv_field("q.a,\"b\""), "\"q.a,\"\"b\"\"\"");
/// ```
pub fn csv_field(name: &str) -> Cow<'_, str> {
    if name.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", name.replace('"', "\"\"")).into()
    } else {
        name.into()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_finite_number_reads_back_exactly() {
        let mut text = NumberText::new();
        // Values whose shortest decimal is long, tiny, huge, negative and subnormal.
        for x in [
            0.1 + 0.2,
            1.0 / 3.0,
            -2.5e-300,
            1.7976931348623157e308,
            5e-324,
            -0.0,
            123456789.0,
        ] {
            let csv: f64 = text.csv(x).parse().unwrap();
            let json: f64 = text.json(x).parse().unwrap();
            assert_eq!(csv.to_bits(), x.to_bits(), "{x}");
            assert_eq!(json.to_bits(), x.to_bits(), "{x}");
            let value: f64 = serde_json::from_value(json_number(x)).unwrap();
            assert_eq!(value.to_bits(), x.to_bits(), "{x}");
        }
    }

    #[test]
    fn non_finite_numbers_are_words_in_csv_and_null_in_json() {
        let mut text = NumberText::new();
        for (x, word) in [
            (f64::NAN, "NaN"),
            (f64::INFINITY, "inf"),
            (f64::NEG_INFINITY, "-inf"),
        ] {
            assert_eq!(text.csv(x), word);
            // Rust's parser reads the CSV words back.
            let back: f64 = text.csv(x).parse().unwrap();
            assert!(back.is_nan() == x.is_nan() && (x.is_nan() || back == x));
            assert_eq!(text.json(x), "null");
            assert_eq!(json_number(x), serde_json::Value::Null);
        }
    }

    #[test]
    fn fields_are_quoted_as_rfc_4180_says() {
        // A field with a comma, quote or line break is enclosed in quotes, quotes doubled.
        assert_eq!(csv_field("a,\"b\"\nc"), "\"a,\"\"b\"\"\nc\"");
        assert_eq!(csv_field("x\ry"), "\"x\ry\"");
        assert!(matches!(csv_field("tau.j1"), Cow::Borrowed("tau.j1")));
    }
}
