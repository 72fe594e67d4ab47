//! The drag's falloff: how far a vertex at distance `d` from the pick point moves, as a
//! fraction `f(d / r)` of the peak offset.
//!
//! Every falloff here has `f(0) = 1`, `f(1) = 0`, zero slope at both ends (a round peak
//! and a rim the surface leaves tangentially) and is `0` beyond the radius, so the moved
//! region joins the still part of the mesh without a crease.

/// A falloff profile `f(t)`, `t = d / r` in `[0, 1]`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Falloff {
    /// `f(t) = (1 - t^2)^2`, the biweight kernel (the default). A polynomial in `d^2`, so
    /// smooth everywhere inside the radius (also at the pick point); C1 at the rim.
    #[default]
    Biweight,
    /// `f(t) = (1 - t)^4 (4 t + 1)`, Wendland's C2 function: also zero curvature at the
    /// rim (a softer edge), but a narrower bump.
    Wendland,
    /// `f(t) = 1 - 3 t^2 + 2 t^3`, smoothstep: a wider, flatter bump; C1 at the rim.
    Smoothstep,
}

impl Falloff {
    /// Every falloff, in session order.
    pub const ALL: [Self; 3] = [Self::Biweight, Self::Wendland, Self::Smoothstep];

    /// The session name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Biweight => "biweight",
            Self::Wendland => "wendland",
            Self::Smoothstep => "smoothstep",
        }
    }

    /// From a session name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|f| f.name() == name)
    }

    /// `f(t)`: `1` at `t = 0`, `0` for `t >= 1`. Negative `t` is read as `|t|`.
    pub fn value(self, t: f64) -> f64 {
        let t = t.abs();
        if t >= 1.0 {
            return 0.0;
        }
        match self {
            Self::Biweight => {
                let s = 1.0 - t * t;
                s * s
            }
            Self::Wendland => {
                let s = 1.0 - t;
                s * s * s * s * (4.0 * t + 1.0)
            }
            Self::Smoothstep => 1.0 - t * t * (3.0 - 2.0 * t),
        }
    }

    /// `f'(t)` for `t` in `[0, 1)`; `0` beyond.
    pub fn slope(self, t: f64) -> f64 {
        let t = t.abs();
        if t >= 1.0 {
            return 0.0;
        }
        match self {
            Self::Biweight => -4.0 * t * (1.0 - t * t),
            Self::Wendland => -20.0 * t * (1.0 - t).powi(3),
            Self::Smoothstep => -6.0 * t * (1.0 - t),
        }
    }
}
