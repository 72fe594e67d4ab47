//! What the flattening's files share: the method and settings, the error, the result, each
//! triangle in its own plane, signed areas and boundary half-edges.

use glam::{DVec2, DVec3};

/// How a panel is flattened.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// LSCM, scaled to the 3D area, then ARAP with boundary-length springs (default).
    #[default]
    Arap,
    /// LSCM alone, scaled to the 3D area (conformal: angles kept, areas not).
    Lscm,
}

impl Method {
    /// The name in sessions (`arap`, `lscm`).
    pub fn name(self) -> &'static str {
        match self {
            Self::Arap => "arap",
            Self::Lscm => "lscm",
        }
    }

    /// The method called `name`.
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "arap" => Some(Self::Arap),
            "lscm" => Some(Self::Lscm),
            _ => None,
        }
    }
}

/// Flattening settings.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct FlattenOptions {
    /// The method (default [`Method::Arap`]).
    pub method: Method,
    /// Weight of a length spring on every boundary edge against the ARAP terms, whose
    /// cotangent weights are about 1 (default 1). The seams' lengths are held exactly
    /// besides (see [`flatten`](super::flatten)'s `runs`); the springs keep each boundary
    /// edge near its own length, so that the held lengths do not bunch at a corner:
    /// measured on the demo's jumpsuit on five bodies (`cargo bench --bench patterns`),
    /// weight 1 lowers the largest strain by up to 7 points at the same mean strain.
    pub boundary_weight: f64,
    /// ARAP iterations at most, free and then with the seams held, each (default 300).
    pub max_iterations: usize,
    /// ARAP stops when an iteration lowers the energy by less than this fraction of it
    /// (default 1e-4: on the demo's jumpsuit on five bodies, the same mean strain to 0.01
    /// points and seams within 0.0001 mm as at 1e-6, in half the time).
    pub tolerance: f64,
}

impl Default for FlattenOptions {
    fn default() -> Self {
        Self {
            method: Method::Arap,
            boundary_weight: 1.0,
            max_iterations: 300,
            tolerance: 1e-4,
        }
    }
}

impl FlattenOptions {
    /// LSCM then ARAP with a free boundary (no springs) to a relative energy change of
    /// 1e-6: the question libigl's `arap_solve` answers, for comparing with it.
    pub fn free() -> Self {
        Self {
            boundary_weight: 0.0,
            tolerance: 1e-6,
            ..Self::default()
        }
    }
}

/// Why a panel could not be flattened.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum FlattenError {
    /// Fewer than one triangle, or a triangle of zero area.
    #[error("the panel has no triangle of positive area")]
    Empty,
    /// The panel's linear system is singular (a panel in pieces, or degenerate triangles).
    #[error(
        "the flattening's system over {unknowns} unknowns is not positive definite (a panel in pieces or with degenerate triangles)"
    )]
    NotPositiveDefinite {
        /// Free unknowns.
        unknowns: usize,
    },
    /// The panel has no boundary (a closed surface cannot be flattened).
    #[error("the panel has no boundary")]
    NoBoundary,
}

/// A flattened panel.
#[derive(Clone, Debug, PartialEq)]
pub struct Flattening {
    /// 2D position of every vertex, m.
    pub uv: Vec<DVec2>,
    /// ARAP iterations run.
    pub iterations: usize,
    /// ARAP energy at the end (0 for a developable panel).
    pub energy: f64,
}

/// Every triangle in its own plane: its corners' 2D coordinates (the first at the origin,
/// the second on `+x`) and the cotangents of its angles.
pub struct Frames {
    /// Local 2D corners per triangle.
    pub local: Vec<[DVec2; 3]>,
    /// Cotangent of the angle at each corner (opposite the edge between the other two).
    pub cot: Vec<[f64; 3]>,
    /// 3D area per triangle.
    pub area: Vec<f64>,
}

impl Frames {
    /// The frames and cotangents of `triangles` over `positions`; [`FlattenError::Empty`] for
    /// none, or for a triangle of zero or non-finite area.
    pub fn new(positions: &[DVec3], triangles: &[[u32; 3]]) -> Result<Self, FlattenError> {
        let mut local = Vec::with_capacity(triangles.len());
        let mut cot = Vec::with_capacity(triangles.len());
        let mut area = Vec::with_capacity(triangles.len());
        for t in triangles {
            let [a, b, c] = t.map(|i| positions[i as usize]);
            let (e1, e2) = (b - a, c - a);
            let n = e1.cross(e2);
            let double = n.length();
            if double == 0.0 || !double.is_finite() {
                return Err(FlattenError::Empty);
            }
            let x = e1 / e1.length();
            let y = n.cross(x) / double;
            local.push([
                DVec2::ZERO,
                DVec2::new(e1.length(), 0.0),
                DVec2::new(e2.dot(x), e2.dot(y)),
            ]);
            let corners = [a, b, c];
            cot.push(std::array::from_fn(|k| {
                let (p, q, r) = (corners[k], corners[(k + 1) % 3], corners[(k + 2) % 3]);
                let (u, v) = (q - p, r - p);
                u.dot(v) / u.cross(v).length()
            }));
            area.push(0.5 * double);
        }
        if local.is_empty() {
            return Err(FlattenError::Empty);
        }
        Ok(Self { local, cot, area })
    }
}

/// Signed area of the 2D triangle `(a, b, c)` (positive counter-clockwise).
pub fn signed_area(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    0.5 * (b - a).perp_dot(c - a)
}

/// The boundary half-edges of a triangle list, in the triangles' orientation: those whose
/// reverse no triangle has. Sorted.
pub fn boundary_half_edges(triangles: &[[u32; 3]]) -> Vec<[u32; 2]> {
    let mut half: Vec<[u32; 2]> = triangles
        .iter()
        .flat_map(|t| (0..3).map(move |k| [t[k], t[(k + 1) % 3]]))
        .collect();
    half.sort_unstable();
    half.iter()
        .filter(|&&[a, b]| half.binary_search(&[b, a]).is_err())
        .copied()
        .collect()
}
