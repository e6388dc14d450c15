//! Model-space coordinates as a user reads them in a message: `(0.894, 0, -0.0144)`, six
//! significant digits, no trailing zeros, exponents only for very large or small values
//! (Rust's `{:?}` of a `DVec3` prints `DVec3(0.8940000000000001, 0.0, -0.0144)`).

use glam::DVec3;
use std::fmt;

/// A point for messages: `format!("near {}", Xyz(p))`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Xyz(pub DVec3);

impl fmt::Display for Xyz {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // Round-off next to the point's size (5e-15 beside 116.75) reads as zero.
        let scale = self.0.abs().max_element();
        let [x, y, z] = self
            .0
            .to_array()
            .map(|c| if c.abs() < 1e-12 * scale { 0.0 } else { c });
        write!(f, "({}, {}, {})", Coord(x), Coord(y), Coord(z))
    }
}

/// One coordinate with six significant digits.
pub struct Coord(pub f64);

impl fmt::Display for Coord {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        if x == 0.0 {
            return f.write_str("0");
        }
        if !x.is_finite() {
            return write!(f, "{x}");
        }
        let magnitude = x.abs().log10().floor() as i32;
        if !(-4..6).contains(&magnitude) {
            // 1.23457e-7, 1.5e9: mantissa without trailing zeros.
            let s = format!("{x:.5e}");
            let (mantissa, exponent) = s.split_once('e').unwrap_or((&s, "0"));
            return write!(f, "{}e{exponent}", trim_zeros(mantissa));
        }
        let decimals = (5 - magnitude).max(0) as usize;
        let s = format!("{x:.decimals$}");
        f.write_str(trim_zeros(&s))
    }
}

/// `1.500` → `1.5`, `2.000` → `2`, `120` unchanged.
fn trim_zeros(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_read_as_a_user_writes_them() {
        let p = Xyz(DVec3::new(0.8940000000000001, 0.0, -0.0144));
        assert_eq!(p.to_string(), "(0.894, 0, -0.0144)");
        assert_eq!(
            Xyz(DVec3::new(1250.5, -3.0, 1e-7)).to_string(),
            "(1250.5, -3, 1e-7)"
        );
        assert_eq!(
            Xyz(DVec3::new(123456789.0, 2.5e-3, 0.1)).to_string(),
            "(1.23457e8, 0.0025, 0.1)"
        );
        assert_eq!(Coord(1.0 / 3.0).to_string(), "0.333333");
        assert_eq!(Coord(2.5e-12).to_string(), "2.5e-12");
        let torus = Xyz(DVec3::new(-34.8412, 5.01547e-15, 116.75));
        assert_eq!(torus.to_string(), "(-34.8412, 0, 116.75)");
    }
}
