//! Which way a body stands: drape's frame is metres, y up, facing +z. A scan from elsewhere
//! may have z up, or face -z or +x; landmarks found on such a body would be nonsense, so it
//! is refused with the axes it seems to have, and [`Frame`] (`--up`, `--front`) turns it
//! into drape's frame.
//!
//! The checks: the body's longest extent is its height, so it must lie along y; the feet
//! are at the bottom (the lowest slice holds two parts apart side by side, the highest one,
//! the head); the toes point forward (the lowest slice reaches farther ahead of the ankles
//! than behind them).

use glam::{DMat3, DVec3};

use crate::mesh::TriMesh;

/// An axis of a file's frame, with its sign.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Axis(pub DVec3);

impl Axis {
    /// `x`, `+x`, `-x`, `y`, ... (no sign is `+`).
    pub fn parse(text: &str) -> Option<Self> {
        let (sign, name) = match text.strip_prefix('-') {
            Some(rest) => (-1.0, rest),
            None => (1.0, text.strip_prefix('+').unwrap_or(text)),
        };
        let v = match name {
            "x" => DVec3::X,
            "y" => DVec3::Y,
            "z" => DVec3::Z,
            _ => return None,
        };
        Some(Self(sign * v))
    }

    /// The name (`+x`, `-z`, ...).
    pub fn name(self) -> String {
        let (k, v) = self
            .0
            .to_array()
            .into_iter()
            .enumerate()
            .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
            .unwrap_or((1, 1.0));
        format!("{}{}", if v < 0.0 { "-" } else { "+" }, ["x", "y", "z"][k])
    }
}

/// A file's frame: which of its axes is up and which is the body's front.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// The file's up axis.
    pub up: Axis,
    /// The file's front axis (the way the body faces).
    pub front: Axis,
}

impl Default for Frame {
    /// drape's own: y up, facing +z.
    fn default() -> Self {
        Self {
            up: Axis(DVec3::Y),
            front: Axis(DVec3::Z),
        }
    }
}

impl Frame {
    /// The frame with `up` and `front`, or why not (the same axis twice).
    pub fn new(up: Axis, front: Axis) -> Result<Self, String> {
        if up.0.cross(front.0) == DVec3::ZERO {
            return Err(format!(
                "up {} and front {} are one axis: give two different axes",
                up.name(),
                front.name()
            ));
        }
        Ok(Self { up, front })
    }

    /// The rotation from the file's frame to drape's (rows: the file's right, up, front).
    pub fn to_drape(self) -> DMat3 {
        let right = self.up.0.cross(self.front.0);
        DMat3::from_cols(right, self.up.0, self.front.0).transpose()
    }

    /// Whether it is drape's own frame.
    pub fn is_identity(self) -> bool {
        self == Self::default()
    }
}

/// Why a body does not stand in drape's frame.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PoseError {
    /// Its longest extent is not along y.
    #[error(
        "the body is {long:.2} m along {axis} and {height:.2} m along y: it is lying down or {axis} is up (give the axes: --up {axis}, or --up -{axis} if it stands on its head)"
    )]
    NotUpright {
        /// The axis of its longest extent.
        axis: &'static str,
        /// That extent, m.
        long: f64,
        /// Its extent along y, m.
        height: f64,
    },
    /// Its feet are at the top.
    #[error(
        "the body stands on its head: its lowest slice is one part and its highest two (the feet); y is down (give --up -y)"
    )]
    UpsideDown,
    /// Its toes point another way than +z.
    #[error("the body faces {facing}: its toes point that way (give --front {facing})")]
    Facing {
        /// Where the toes point.
        facing: String,
    },
}

/// Checks that `mesh` stands in drape's frame: y up (its longest extent, feet at the
/// bottom), facing +z (the toes forward).
pub fn check_pose(mesh: &TriMesh) -> Result<(), PoseError> {
    let Some((lo, hi)) = mesh.bounds() else {
        return Ok(());
    };
    let size = hi - lo;
    if size.x > size.y || size.z > size.y {
        let (axis, long) = if size.x >= size.z { ("x", size.x) } else { ("z", size.z) };
        return Err(PoseError::NotUpright {
            axis,
            long,
            height: size.y,
        });
    }
    let slab = |from: f64, to: f64| -> Vec<DVec3> {
        mesh.positions
            .iter()
            .filter(|p| (lo.y + from * size.y..=lo.y + to * size.y).contains(&p.y))
            .copied()
            .collect()
    };
    let (bottom, top) = (slab(0.0, 0.03), slab(0.97, 1.0));
    if parts_across(&bottom, size.y) == 1 && parts_across(&top, size.y) >= 2 {
        return Err(PoseError::UpsideDown);
    }
    // The toes: the lowest slice's reach ahead of the ankles' centre against behind it.
    let ankles = slab(0.04, 0.07);
    if bottom.is_empty() || ankles.is_empty() {
        return Ok(());
    }
    let centre = ankles.iter().sum::<DVec3>() / ankles.len() as f64;
    let reach = |d: DVec3| {
        bottom
            .iter()
            .map(|p| (*p - centre).dot(d))
            .fold(f64::NEG_INFINITY, f64::max)
    };
    // How much farther the slice reaches one way than the opposite; a foot reaches its
    // toes' length ahead of the ankle and a heel's behind. A scan without feet has no such
    // lead (under 2% of the height either way) and is not judged.
    let lead = |d: DVec3| reach(d) - reach(-d);
    let (best, most) = [DVec3::Z, -DVec3::Z, DVec3::X, -DVec3::X]
        .into_iter()
        .map(|d| (d, lead(d)))
        .fold((DVec3::Z, f64::NEG_INFINITY), |a, b| if b.1 > a.1 { b } else { a });
    let margin = 0.02 * size.y;
    if best != DVec3::Z && most > margin && most - lead(DVec3::Z) > margin {
        return Err(PoseError::Facing {
            facing: Axis(best).name(),
        });
    }
    Ok(())
}

/// How many parts apart side by side the points fall into: runs of their sorted x (or z,
/// whichever gives more) with gaps wider than 3% of the body's height `height` (feet stand
/// farther apart; a head's vertices lie nearer one another).
fn parts_across(points: &[DVec3], height: f64) -> usize {
    let parts = |coord: fn(&DVec3) -> f64| {
        let mut xs: Vec<f64> = points.iter().map(coord).collect();
        if xs.is_empty() {
            return 0;
        }
        xs.sort_by(f64::total_cmp);
        1 + xs.windows(2).filter(|w| w[1] - w[0] > 0.03 * height).count()
    };
    parts(|p| p.x).max(parts(|p| p.z))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_frame_maps_its_up_to_y_and_its_front_to_z() {
        let f = Frame::new(Axis::parse("z").unwrap(), Axis::parse("-y").unwrap()).unwrap();
        let m = f.to_drape();
        assert!((m * DVec3::Z - DVec3::Y).length() < 1e-12);
        assert!((m * -DVec3::Y - DVec3::Z).length() < 1e-12);
        assert!((m.determinant() - 1.0).abs() < 1e-12);
        assert!(Frame::new(Axis::parse("x").unwrap(), Axis::parse("-x").unwrap()).is_err());
        assert_eq!(Axis::parse("-z").unwrap().name(), "-z");
        assert_eq!(Axis::parse("q"), None);
    }
}
