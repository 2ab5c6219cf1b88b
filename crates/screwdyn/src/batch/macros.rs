//! Straight-line lane arithmetic: arrays and dot products of `3` or `6` entries written out,
//! so that the compiler vectorises across the lanes, not across the entries.

/// `[e(0), e(1), …]`: an array of `3` or `6` entries, written out (no loop, no closure), so
/// that the compiler sees straight-line lane arithmetic. A loop of three here would be
/// vectorised across its iterations (gathering one lane at a time) instead of across the lanes.
macro_rules! each {
    (3, |$k:ident| $e:expr) => {
        [
            {
                let $k = 0;
                $e
            },
            {
                let $k = 1;
                $e
            },
            {
                let $k = 2;
                $e
            },
        ]
    };
    (6, |$k:ident| $e:expr) => {
        [
            {
                let $k = 0;
                $e
            },
            {
                let $k = 1;
                $e
            },
            {
                let $k = 2;
                $e
            },
            {
                let $k = 3;
                $e
            },
            {
                let $k = 4;
                $e
            },
            {
                let $k = 5;
                $e
            },
        ]
    };
}

/// A 3×3 array of entries `e(i, j)`, written out.
macro_rules! each33 {
    (|$i:ident, $j:ident| $e:expr) => {
        [
            each!(3, |$j| {
                let $i = 0;
                $e
            }),
            each!(3, |$j| {
                let $i = 1;
                $e
            }),
            each!(3, |$j| {
                let $i = 2;
                $e
            }),
        ]
    };
}

/// `Σ_k a(k) b(k)` over `3` or `6` terms in index order, each product added with one rounding
/// ([`Lanes::mul_add`]); `dot!(n, |k| a, b; c)` starts the sum from `c` instead of the first
/// product. `a(k)` must be lanes, `b(k)` lanes or a number.
macro_rules! dot {
    (3, |$k:ident| $a:expr, $b:expr $(; $c:expr)?) => {{
        let acc = dot!(@first $k, $a, $b $(; $c)?);
        let acc = { let $k = 1; ($a).mul_add($b, acc) };
        { let $k = 2; ($a).mul_add($b, acc) }
    }};
    (6, |$k:ident| $a:expr, $b:expr $(; $c:expr)?) => {{
        let acc = dot!(@first $k, $a, $b $(; $c)?);
        let acc = { let $k = 1; ($a).mul_add($b, acc) };
        let acc = { let $k = 2; ($a).mul_add($b, acc) };
        let acc = { let $k = 3; ($a).mul_add($b, acc) };
        let acc = { let $k = 4; ($a).mul_add($b, acc) };
        { let $k = 5; ($a).mul_add($b, acc) }
    }};
    (@first $k:ident, $a:expr, $b:expr) => {{ let $k = 0; $a * $b }};
    (@first $k:ident, $a:expr, $b:expr; $c:expr) => {{ let $k = 0; ($a).mul_add($b, $c) }};
}
