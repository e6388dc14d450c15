//! Error type shared by all constructors of the crate.

use thiserror::Error;

/// Why a curve or surface could not be built from the given data.
///
/// Evaluation never fails; only construction validates its input, so that every
/// constructed object is guaranteed to have finite data and strictly increasing
/// parameters (which the evaluators divide by).
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum NativeError {
    /// Not enough points (or grid lines) to define even one segment/patch.
    #[error("too few points: needed at least {needed}, got {got}")]
    TooFewPoints { needed: usize, got: usize },
    /// `points[index]` and `points[index + 1]` coincide, so the chord-length
    /// parameter interval between them would be empty.
    #[error("points {index} and {} coincide (zero chord length)", index + 1)]
    CoincidentPoints { index: usize },
    /// Two consecutive grid lines of a surface coincide entirely: the averaged
    /// chord length between grid line `index` and `index + 1` along `axis`
    /// (`'u'` or `'v'`) is zero.
    #[error("grid lines {index} and {} along {axis} coincide (zero averaged chord length)", index + 1)]
    CoincidentGridLines { axis: char, index: usize },
    /// Parallel input slices have different lengths (e.g. points vs tangents).
    #[error("length mismatch: expected {expected} items, got {got}")]
    LengthMismatch { expected: usize, got: usize },
    /// Grid row `row` has a different length than row 0.
    #[error("ragged grid: row {row} has {got} points, expected {expected}")]
    RaggedGrid {
        row: usize,
        expected: usize,
        got: usize,
    },
    /// A point or tangent of a curve at `index` has a NaN or infinite coordinate.
    #[error("non-finite coordinate at index {index}")]
    NonFinite { index: usize },
    /// Given parameters along `axis` are not finite and strictly increasing at `index`.
    #[error("parameters along {axis} are not finite and strictly increasing at index {index}")]
    BadParams { axis: char, index: usize },
    /// Grid point `grid[row][col]` has a NaN or infinite coordinate.
    #[error("non-finite coordinate at grid point ({row}, {col})")]
    NonFiniteGrid { row: usize, col: usize },
}
