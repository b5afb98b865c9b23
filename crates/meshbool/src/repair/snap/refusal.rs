//! Why a change was not made: the gate that refused it, or a neighbourhood not gathered
//! yet.

/// Why a change was refused: the first gate that refused it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Refusal {
    Manifold,
    Inversion,
    SelfIntersection,
    Distance,
    Volume,
    Seam,
    NoGain,
}

/// Why a change was not made.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Stop {
    /// A gate refused it.
    Refused(Refusal),
    /// The neighbourhood it needs is not gathered yet: the next round.
    Later,
}

/// What a gate answers: the value it found, or why the change stops.
pub(super) type Gate<T> = std::result::Result<T, Stop>;

/// A refusal by gate `r`.
pub(super) fn refuse<T>(r: Refusal) -> Gate<T> {
    Err(Stop::Refused(r))
}
