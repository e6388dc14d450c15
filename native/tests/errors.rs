use glam::DVec3;
use tetrafoil_native::{FergusonCurve, FergusonSurface, NativeError};

#[test]
fn too_few_points() {
    assert_eq!(
        FergusonCurve::interpolate(&[DVec3::ONE]),
        Err(NativeError::TooFewPoints { needed: 2, got: 1 })
    );
    assert_eq!(
        FergusonCurve::interpolate(&[]),
        Err(NativeError::TooFewPoints { needed: 2, got: 0 })
    );
    assert_eq!(
        FergusonCurve::with_tangents(&[DVec3::ONE], &[DVec3::X]),
        Err(NativeError::TooFewPoints { needed: 2, got: 1 })
    );
    assert_eq!(
        FergusonSurface::interpolate(&[vec![DVec3::ZERO, DVec3::X]]),
        Err(NativeError::TooFewPoints { needed: 2, got: 1 })
    );
    assert_eq!(
        FergusonSurface::interpolate(&[vec![DVec3::ZERO], vec![DVec3::X]]),
        Err(NativeError::TooFewPoints { needed: 2, got: 1 })
    );
}

#[test]
fn coincident_consecutive_points() {
    let pts = [DVec3::ZERO, DVec3::X, DVec3::X, DVec3::Y];
    assert_eq!(
        FergusonCurve::interpolate(&pts),
        Err(NativeError::CoincidentPoints { index: 1 })
    );
    assert_eq!(
        FergusonCurve::with_tangents(&pts, &[DVec3::X; 4]),
        Err(NativeError::CoincidentPoints { index: 1 })
    );
    // Non-consecutive repeats (a closed loop) are fine.
    assert!(FergusonCurve::interpolate(&[DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ZERO]).is_ok());
}

#[test]
fn coincident_grid_lines() {
    let row = |x: f64| vec![DVec3::new(x, 0.0, 0.0), DVec3::new(x, 1.0, 0.0)];
    assert_eq!(
        FergusonSurface::interpolate(&[row(0.0), row(1.0), row(1.0)]),
        Err(NativeError::CoincidentGridLines {
            axis: 'u',
            index: 1
        })
    );
    let grid = vec![
        vec![DVec3::ZERO, DVec3::ZERO, DVec3::Y],
        vec![DVec3::X, DVec3::X, DVec3::X + DVec3::Y],
    ];
    assert_eq!(
        FergusonSurface::interpolate(&grid),
        Err(NativeError::CoincidentGridLines {
            axis: 'v',
            index: 0
        })
    );
    // A single collapsed grid line (e.g. a pole) is allowed: params are averaged.
    let pole = vec![
        vec![DVec3::ZERO, DVec3::ZERO, DVec3::ZERO],
        vec![DVec3::X, DVec3::X + DVec3::Y, DVec3::X + 2.0 * DVec3::Y],
    ];
    let s = FergusonSurface::interpolate(&pole).unwrap();
    assert_eq!(s.point(0.0, s.v_params()[1]), DVec3::ZERO);
}

#[test]
fn ragged_grid() {
    let grid = vec![
        vec![DVec3::ZERO, DVec3::Y],
        vec![DVec3::X, DVec3::X + DVec3::Y],
        vec![DVec3::X * 2.0],
    ];
    assert_eq!(
        FergusonSurface::interpolate(&grid),
        Err(NativeError::RaggedGrid {
            row: 2,
            expected: 2,
            got: 1
        })
    );
}

#[test]
fn length_mismatch() {
    assert_eq!(
        FergusonCurve::with_tangents(&[DVec3::ZERO, DVec3::X, DVec3::Y], &[DVec3::X; 2]),
        Err(NativeError::LengthMismatch {
            expected: 3,
            got: 2
        })
    );
}

#[test]
fn non_finite_input() {
    let nan = DVec3::new(0.0, f64::NAN, 0.0);
    assert_eq!(
        FergusonCurve::interpolate(&[DVec3::ZERO, nan]),
        Err(NativeError::NonFinite { index: 1 })
    );
    assert_eq!(
        FergusonCurve::with_tangents(&[DVec3::ZERO, DVec3::X], &[DVec3::INFINITY, DVec3::X]),
        Err(NativeError::NonFinite { index: 0 })
    );
    assert_eq!(
        FergusonSurface::interpolate(&[vec![DVec3::ZERO, DVec3::Y], vec![DVec3::X, nan]]),
        Err(NativeError::NonFiniteGrid { row: 1, col: 1 })
    );
}

#[test]
fn errors_display() {
    let e = NativeError::CoincidentPoints { index: 3 };
    assert_eq!(e.to_string(), "points 3 and 4 coincide (zero chord length)");
    let e = NativeError::RaggedGrid {
        row: 2,
        expected: 5,
        got: 4,
    };
    assert!(e.to_string().contains("row 2"));
}
