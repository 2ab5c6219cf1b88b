//! The one sentence for a numeric setting out of its range, naming the setting as the caller
//! spells it: `dt must be positive (got 0); it is the integration step in seconds`.

use crate::error::{Error, Result};

/// The values a setting may take.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Range {
    /// Finite and `> 0`.
    Positive,
    /// Finite and `≥ 0`.
    NonNegative,
}

/// `Err(InvalidArgument)` naming `name` (and saying what it is, `meaning`) when `x` is outside
/// `range`: NaN or the wrong sign reads "must be positive/non-negative", an infinity of the
/// right sign "must be finite".
pub(crate) fn check(name: &str, x: f64, range: Range, meaning: &str) -> Result<()> {
    let (inside, must) = match range {
        Range::Positive => (x > 0.0, "positive"),
        Range::NonNegative => (x >= 0.0, "non-negative"),
    };
    let must = if !inside {
        must
    } else if !x.is_finite() {
        "finite"
    } else {
        return Ok(());
    };
    Err(Error::InvalidArgument(format!(
        "{name} must be {must} (got {x}); it is {meaning}"
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn out_of_range_values_are_named_with_the_rule_they_break() {
        let say = |x, r| check("dt", x, r, "the step").unwrap_err().to_string();
        assert_eq!(
            say(0.0, Range::Positive),
            "dt must be positive (got 0); it is the step"
        );
        assert_eq!(
            say(f64::NAN, Range::NonNegative),
            "dt must be non-negative (got NaN); it is the step"
        );
        assert_eq!(
            say(f64::INFINITY, Range::Positive),
            "dt must be finite (got inf); it is the step"
        );
        assert!(say(-1e-3, Range::NonNegative).contains("non-negative (got -0.001)"));
        assert!(check("dt", 0.0, Range::NonNegative, "").is_ok());
        assert!(check("dt", 1e-300, Range::Positive, "").is_ok());
    }
}
