//! Shared building blocks: the cubic Hermite basis, interval lookup and the
//! tangent estimate used by both curves and surfaces (so that a surface grid
//! line gets exactly the tangents a curve through the same data would get,
//! given the same parameters).

use glam::DVec3;

/// Cubic Hermite basis on s ∈ [0,1] in the order
/// `[H0 (value at 0), H1 (value at 1), H2 (slope at 0), H3 (slope at 1)]`,
/// together with its first and second derivatives with respect to s.
pub(crate) fn basis(s: f64) -> ([f64; 4], [f64; 4], [f64; 4]) {
    let s2 = s * s;
    let s3 = s2 * s;
    let f = [
        2.0 * s3 - 3.0 * s2 + 1.0,
        -2.0 * s3 + 3.0 * s2,
        s3 - 2.0 * s2 + s,
        s3 - s2,
    ];
    let d1 = [
        6.0 * s2 - 6.0 * s,
        -6.0 * s2 + 6.0 * s,
        3.0 * s2 - 4.0 * s + 1.0,
        3.0 * s2 - 2.0 * s,
    ];
    let d2 = [
        12.0 * s - 6.0,
        -12.0 * s + 6.0,
        6.0 * s - 4.0,
        6.0 * s - 2.0,
    ];
    (f, d1, d2)
}

/// Index `k` of the interval `[params[k], params[k+1]]` used to evaluate at `t`.
///
/// Values outside the range map to the first/last interval so that the end
/// cubic is extrapolated; NaN maps to interval 0 (and then propagates as NaN).
/// `params` must be strictly increasing with at least two entries.
pub(crate) fn interval(params: &[f64], t: f64) -> usize {
    params
        .partition_point(|&p| p <= t)
        .saturating_sub(1)
        .min(params.len() - 2)
}

/// Chord-weighted tangent estimate dV/dt at every node of `values` sampled at
/// strictly increasing `params`.
///
/// Interior nodes use the Bessel tangent, i.e. the derivative of the parabola
/// through the node and its two neighbours; it is exact for quadratics in t and
/// only depends on local data. End nodes use the derivative of the parabola
/// through the first (last) three nodes ("quadratic end condition"), which is
/// consistent with the interior choice. With two nodes the chord slope is used,
/// i.e. a straight line traversed at constant speed.
pub(crate) fn estimate_tangents(params: &[f64], values: &[DVec3]) -> Vec<DVec3> {
    let n = values.len();
    debug_assert_eq!(n, params.len());
    debug_assert!(n >= 2);
    let h: Vec<f64> = params.windows(2).map(|w| w[1] - w[0]).collect();
    let d: Vec<DVec3> = (0..n - 1)
        .map(|k| (values[k + 1] - values[k]) / h[k])
        .collect();
    if n == 2 {
        return vec![d[0], d[0]];
    }
    let mut t = Vec::with_capacity(n);
    t.push(d[0] - (d[1] - d[0]) * (h[0] / (h[0] + h[1])));
    for k in 1..n - 1 {
        t.push((d[k - 1] * h[k] + d[k] * h[k - 1]) / (h[k - 1] + h[k]));
    }
    let m = n - 2;
    t.push(d[m] + (d[m] - d[m - 1]) * (h[m] / (h[m - 1] + h[m])));
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tangents_exact_for_quadratics_on_uneven_params() {
        let params = [0.0, 0.3, 1.1, 1.5, 2.75];
        let f = |t: f64| DVec3::new(1.0 + 2.0 * t - 0.5 * t * t, 3.0 * t * t, -t);
        let df = |t: f64| DVec3::new(2.0 - t, 6.0 * t, -1.0);
        let values: Vec<DVec3> = params.iter().map(|&t| f(t)).collect();
        let tangents = estimate_tangents(&params, &values);
        for (&t, tan) in params.iter().zip(&tangents) {
            assert!((*tan - df(t)).length() < 1e-12, "t={t}: {tan} vs {}", df(t));
        }
    }

    #[test]
    fn interval_lookup_clamps_and_handles_nodes() {
        let p = [0.0, 1.0, 2.0, 3.0];
        assert_eq!(interval(&p, -5.0), 0);
        assert_eq!(interval(&p, 0.0), 0);
        assert_eq!(interval(&p, 1.0), 1);
        assert_eq!(interval(&p, 2.5), 2);
        assert_eq!(interval(&p, 3.0), 2);
        assert_eq!(interval(&p, 9.0), 2);
        assert_eq!(interval(&p, f64::NAN), 0);
    }
}
