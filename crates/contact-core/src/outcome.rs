//! The words a report answers in: which method ran, why refinement stopped,
//! what an estimate is based on, what a warning or a note is about and which
//! stage a solve is in. Each is a closed
//! set, so a client can match on it and the reply's schema can list it; the
//! wire layer maps each variant to its own enum by an exhaustive match, so a
//! variant added here and not on the wire does not compile, and
//! `contact`'s schema test checks every `ALL` entry against the schema.

/// A closed set of snake_case names: the enum, `ALL` (every variant, in
/// order) and `as_str` (the name on the wire).
macro_rules! named {
    ($(#[$meta:meta])* $name:ident { $($(#[$vmeta:meta])* $variant:ident = $text:literal,)+ }) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum $name {
            $($(#[$vmeta])* $variant,)+
        }

        impl $name {
            /// Every variant, in declaration order.
            pub const ALL: &'static [$name] = &[$($name::$variant,)+];

            /// The variant's name on the wire.
            pub const fn as_str(self) -> &'static str {
                match self {
                    $($name::$variant => $text,)+
                }
            }
        }

        impl PartialEq<&str> for $name {
            fn eq(&self, other: &&str) -> bool {
                self.as_str() == *other
            }
        }

        impl std::fmt::Display for $name {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.as_str())
            }
        }
    };
}

named! {
    /// The stage a solve is in, as progress reports and timeouts name it.
    ProgressStage {
        /// Reading or generating the meshes.
        Mesh = "mesh",
        /// The stiffness, the loads and the contact rows.
        Assembly = "assembly",
        /// The sparse Cholesky factorization of K.
        Factorization = "factorization",
        /// K's inverse condensed onto the contact rows.
        Condensation = "condensation",
        /// The contact iterations.
        ContactSolve = "contact_solve",
        /// Pressures, zones, certificate and fields.
        Post = "post",
        /// The error estimate's companion solve.
        Estimate = "estimate",
    }
}

named! {
    /// Whether the answer can be used.
    Status {
        /// Converged; the certificate is within the tolerance.
        Solved = "solved",
        /// Stopped at the iteration cap; the certificate tells how far off it is.
        MaxIterations = "max_iterations",
        /// The linear algebra lost accuracy; the numbers must not be trusted.
        NumericalError = "numerical_error",
    }
}

named! {
    /// The contact method that produced the answer (after `auto` chose).
    MethodRan {
        /// Condensed active set (semismooth Newton on the LCP).
        ActiveSet = "active_set",
        /// Condensed interior point (Clarabel).
        InteriorPoint = "interior_point",
        /// Exterior penalty: inexact by construction.
        Penalty = "penalty",
        /// Augmented Lagrangian on the penalty's springs.
        AugmentedLagrangian = "augmented_lagrangian",
        /// Log barrier: inexact by construction.
        Barrier = "barrier",
        /// Active set on the full saddle-point system.
        ActiveSetFull = "active_set_full",
        /// Interior point on the full QP.
        InteriorPointFull = "interior_point_full",
    }
}

named! {
    /// Why tolerance-driven refinement stopped.
    StopReason {
        /// Every pair's estimate met the targets.
        Reached = "reached",
        /// Nothing is in contact: no contact error to reduce.
        NoContact = "no_contact",
        /// The last round's answer was not `solved`.
        NotSolved = "not_solved",
        /// `accuracy.max_rounds` rounds ran.
        MaxRounds = "max_rounds",
        /// The next round would pass `accuracy.max_dofs`.
        MaxDofs = "max_dofs",
        /// The next round would not fit the time left.
        TimeLimit = "time_limit",
        /// The next round passed the service's size limit.
        SizeLimit = "size_limit",
        /// A round could not be solved; the last answer stands.
        RoundFailed = "round_failed",
        /// Two rounds without progress.
        NotConverging = "not_converging",
    }
}

named! {
    /// What a pair's error estimate is based on.
    EstimateBasis {
        /// Against a companion with every element twice as large (a given
        /// mesh's region meshed again so).
        TwoLevel = "two_level",
        /// A given mesh whose region cannot be meshed again (a hole, more
        /// than one boundary loop) against itself with every triangle split
        /// in four.
        TwoLevelFiner = "two_level_finer",
        /// No companion could be solved: the zone ends only.
        ZoneEdges = "zone_edges",
        /// No estimate at all: a 3D solid on a given mesh (no companion is
        /// made for it), or whose companion did not solve (the notes say
        /// why).
        NoEstimate = "none",
    }
}

named! {
    /// What a warning is about (`solution::validity`, `adapt`).
    WarningCode {
        /// Strain past the small-strain theory's range.
        LargeStrain = "large_strain",
        /// A rotation past the linearized kinematics' range.
        LargeRotation = "large_rotation",
        /// A body moves by a large share of its size (equilibrium is written
        /// on the undeformed shape).
        LargeDisplacement = "large_displacement",
        /// A body held only by contact turns about it.
        Rolling = "rolling",
        /// Too few elements across a contact zone.
        CoarseContactZone = "coarse_contact_zone",
        /// A zone reaching far onto an obstacle's curved part.
        LargeContactZone = "large_contact_zone",
        /// Contact points slide far across a curved obstacle (the linearized
        /// distance errs).
        GapLinearization = "gap_linearization",
        /// Refinement stopped short of `settings.accuracy`'s targets.
        ToleranceNotReached = "tolerance_not_reached",
        /// A frictional contact point whose slip relative to the other
        /// surface the supports prescribe (`solution::prescribed_slip`): its
        /// friction force is μ λ, with no bounded limit as μ grows.
        PrescribedSlip = "prescribed_slip",
    }
}

named! {
    /// What a note is about. A note explains the answer (what ran, what it
    /// holds at 0, why a step fell short); a warning questions it.
    NoteKind {
        /// A two-body pair turned round: the much stiffer body is the other
        /// side, and the pair is reported that way (`scene::validate`).
        PairSwapped = "pair_swapped",
        /// A nearly incompressible body on linear triangles, which lock.
        NearlyIncompressible = "nearly_incompressible",
        /// A nearly incompressible body on T6 ran the locking-free P2–P0
        /// element.
        P2P0Element = "p2_p0_element",
        /// A rigid motion (or a combination) that nothing determines,
        /// reported at 0.
        UndeterminedMotion = "undetermined_motion",
        /// `auto`'s active set did not converge; the interior point ran.
        MethodFallback = "method_fallback",
        /// Too many frictional rows for the condensed formulation: solved on
        /// the full system.
        FullSystem = "full_system",
        /// The answer holds a number that is not finite.
        NonFinite = "non_finite",
        /// The contact forces are far beyond what the loads and the
        /// deformation can balance (`certificate::force_excess`): they cancel
        /// each other and must not be read.
        UnboundedForces = "unbounded_forces",
        /// The error estimate's companion was not solved (too large, too
        /// slow, failed): only the zone ends are estimated.
        EstimateLimited = "estimate_limited",
        /// Nothing is in contact: `settings.accuracy` did not refine.
        NotRefined = "not_refined",
        /// A frictional step with a load-controlled punch ran out of
        /// iterations: the punch most likely slides.
        SlidingPunch = "sliding_punch",
        /// A frictional step with a body held only by contact ran out of
        /// iterations: whether it slides or the iteration fell short.
        UnsettledBody = "unsettled_body",
    }
}

/// A note on an answer: its kind and its text (numbers in the request's
/// units).
#[derive(Debug, Clone, PartialEq)]
pub struct Note {
    pub kind: NoteKind,
    pub text: String,
}

impl Note {
    pub fn new(kind: NoteKind, text: impl Into<String>) -> Self {
        Note {
            kind,
            text: text.into(),
        }
    }
}

impl std::fmt::Display for Note {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.text)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Names are unique snake_case words within each set: they are JSON
    /// enum values and Python identifiers' sources.
    #[test]
    fn names_are_distinct_snake_case() {
        let sets: [Vec<&str>; 7] = [
            MethodRan::ALL.iter().map(|v| v.as_str()).collect(),
            StopReason::ALL.iter().map(|v| v.as_str()).collect(),
            EstimateBasis::ALL.iter().map(|v| v.as_str()).collect(),
            WarningCode::ALL.iter().map(|v| v.as_str()).collect(),
            NoteKind::ALL.iter().map(|v| v.as_str()).collect(),
            ProgressStage::ALL.iter().map(|v| v.as_str()).collect(),
            Status::ALL.iter().map(|v| v.as_str()).collect(),
        ];
        for names in sets {
            let mut sorted = names.clone();
            sorted.sort_unstable();
            sorted.dedup();
            assert_eq!(sorted.len(), names.len(), "{names:?}");
            for n in names {
                assert!(
                    n.chars()
                        .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_'),
                    "{n}"
                );
            }
        }
    }
}
