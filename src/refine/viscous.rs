//! The first layer's height from a y⁺ target, by the flat-plate estimate: turbulent skin
//! friction Cf = 0.026 Re^(−1/7) (White's power law), friction velocity u_τ = U √(Cf/2), so
//! y = y⁺ ν / u_τ = y⁺ L / (Re √(Cf/2)), L the length the Reynolds number is based on, in the
//! model's unit. An estimate for the wall spacing before any solution exists; solvers report
//! the y⁺ reached.

/// A viscous wall's first-layer target.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WallTarget {
    pub yplus: f64,
    pub reynolds: f64,
    /// The Reynolds number's reference length (a chord), in the model's unit.
    pub length: f64,
}

impl WallTarget {
    /// A target after checking each number is positive; the error names the one that is not
    /// (`yplus`, `reynolds` or `chord`).
    pub fn new(yplus: f64, reynolds: f64, length: f64) -> Result<Self, (&'static str, String)> {
        for (key, v) in [("yplus", yplus), ("reynolds", reynolds), ("chord", length)] {
            if !(v.is_finite() && v > 0.0) {
                return Err((key, format!("must be a positive number, got {v}")));
            }
        }
        Ok(Self {
            yplus,
            reynolds,
            length,
        })
    }

    /// Cf = 0.026 Re^(−1/7).
    pub fn skin_friction(&self) -> f64 {
        0.026 * self.reynolds.powf(-1.0 / 7.0)
    }

    /// The first layer's height.
    pub fn first(&self) -> f64 {
        self.yplus * self.length / (self.reynolds * (0.5 * self.skin_friction()).sqrt())
    }

    /// What was estimated, for the report.
    pub fn describe(&self) -> String {
        format!(
            "first {:.4e} from y+ {} at Re {:.4e} on length {} (flat plate: Cf = 0.026 Re^-1/7 = {:.5})",
            self.first(),
            self.yplus,
            self.reynolds,
            self.length,
            self.skin_friction()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_m6_wall_at_y_plus_one() {
        // Re 11.7e6 on the mean aerodynamic chord 0.646 m: Cf = 0.026 / 11.7e6^(1/7).
        let t = WallTarget::new(1.0, 11.7e6, 0.646).unwrap();
        let cf = 0.026 / 11.7e6f64.powf(1.0 / 7.0);
        assert!((t.skin_friction() - cf).abs() < 1e-15);
        assert!((cf - 0.002542).abs() < 1e-5, "{cf}");
        let first = 0.646 / (11.7e6 * (cf / 2.0).sqrt());
        assert!((t.first() - first).abs() < 1e-18);
        assert!((first - 1.549e-6).abs() < 5e-9, "{first}");
        // Linear in y+ and in the length; the model in millimetres gives millimetres.
        let mm = WallTarget::new(2.0, 11.7e6, 646.0).unwrap();
        assert!((mm.first() / t.first() - 2000.0).abs() < 1e-9);
        assert!(t.describe().contains("Cf = 0.026 Re^-1/7 = 0.00254"));
        assert_eq!(WallTarget::new(1.0, 0.0, 1.0).unwrap_err().0, "reynolds");
        assert_eq!(WallTarget::new(1.0, 1e6, -1.0).unwrap_err().0, "chord");
    }
}
