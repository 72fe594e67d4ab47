//! Body partitions A-G (\[collide\] section 4.1, table 1): height bands between landmark
//! rings, each with the collision test and the response rule its shape calls for.

use super::BodyMesh;
use super::landmarks::{LandmarkKind, Landmarks};
use super::rings::{BodyRing, RingError, RingPick, pick_rings};

/// The seven partitions, bottom to top.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize, serde::Deserialize)]
pub enum PartitionId {
    /// Legs.
    A,
    /// Crotch.
    B,
    /// Hip.
    C,
    /// Abdomen.
    D,
    /// Chest.
    E,
    /// Shoulder.
    F,
    /// Neck.
    G,
}

impl PartitionId {
    /// All, bottom to top.
    pub const ALL: [Self; 7] = [Self::A, Self::B, Self::C, Self::D, Self::E, Self::F, Self::G];

    /// The letter.
    pub fn letter(self) -> &'static str {
        match self {
            Self::A => "A",
            Self::B => "B",
            Self::C => "C",
            Self::D => "D",
            Self::E => "E",
            Self::F => "F",
            Self::G => "G",
        }
    }

    /// The body region.
    pub fn region(self) -> &'static str {
        match self {
            Self::A => "legs",
            Self::B => "crotch",
            Self::C => "hip",
            Self::D => "abdomen",
            Self::E => "chest",
            Self::F => "shoulder",
            Self::G => "neck",
        }
    }

    /// How garment vertices in this partition are tested (\[collide\] table 1 and section 4.2:
    /// legs and abdomen use the cheap line-line test in the horizontal section).
    pub fn method(self) -> DetectionMethod {
        match self {
            Self::A | Self::D => DetectionMethod::LineLine,
            _ => DetectionMethod::PointFace,
        }
    }

    /// Which direction a penetrating vertex is pushed out along (\[collide\] section 5.2).
    pub fn response(self) -> ResponseRule {
        match self {
            Self::A | Self::B | Self::C => ResponseRule::RingCentre,
            Self::D => ResponseRule::BodyNormal,
            Self::F => ResponseRule::ViewDirection,
            Self::E | Self::G => ResponseRule::VertexNormal,
        }
    }
}

/// Collision test of a partition.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DetectionMethod {
    /// The vertex's short normal segment against the body triangles.
    PointFace,
    /// The vertex's normal segment against the body ring polyline in the horizontal section.
    LineLine,
}

/// Response direction rule of a partition.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ResponseRule {
    /// Along the ray from the ring's global or local centre (legs, crotch, hip).
    RingCentre,
    /// Along the normal of the body triangle hit (abdomen: avoids self-collision).
    BodyNormal,
    /// Along the view direction for vertices that must stay on a contour (shoulder).
    ViewDirection,
    /// Along the garment vertex normal.
    VertexNormal,
}

/// One partition.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Partition {
    /// Which.
    pub id: PartitionId,
    /// Lower bound, m.
    pub lower_y: f64,
    /// Upper bound, m.
    pub upper_y: f64,
    /// Collision test.
    pub method: DetectionMethod,
    /// Response rule.
    pub response: ResponseRule,
    /// Body triangles overlapping the band widened by the margin, ascending.
    #[serde(skip)]
    pub triangles: Vec<u32>,
    /// Number of those triangles.
    pub triangle_count: usize,
    /// The body sections at its bounds (both legs for A).
    #[serde(skip)]
    pub rings: Vec<BodyRing>,
}

/// Partition settings.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct PartitionOptions {
    /// Margin band added above and below each partition, as a fraction of body height,
    /// so that a vertex near a boundary still sees the triangles across it.
    /// Default value: 0.01.
    pub margin_fraction: f64,
}

impl Default for PartitionOptions {
    fn default() -> Self {
        Self { margin_fraction: 0.01 }
    }
}

/// The bounds of each partition, from the landmarks:
/// A floor..crotch, B crotch..hip, C hip..(hip+waist)/2, D ..(waist+bust)/2,
/// E ..armpit, F armpit..front neck, G front neck..top.
pub fn partition_bounds(landmarks: &Landmarks, floor: f64, top: f64) -> [(PartitionId, f64, f64); 7] {
    let h = |k| landmarks.height(k);
    let crotch = h(LandmarkKind::Crotch);
    let hip = h(LandmarkKind::Hip);
    let waist = h(LandmarkKind::Waist);
    let bust = h(LandmarkKind::Bust);
    let armpit = h(LandmarkKind::Armpit);
    let front_neck = h(LandmarkKind::FrontNeck);
    let hw = 0.5 * (hip + waist);
    let wb = 0.5 * (waist + bust);
    [
        (PartitionId::A, floor, crotch),
        (PartitionId::B, crotch, hip),
        (PartitionId::C, hip, hw),
        (PartitionId::D, hw, wb),
        (PartitionId::E, wb, armpit),
        (PartitionId::F, armpit, front_neck),
        (PartitionId::G, front_neck, top),
    ]
}

/// Builds the partitions: bounds, triangles (with margin) and boundary rings.
pub fn partitions(
    body: &BodyMesh,
    landmarks: &Landmarks,
    options: &PartitionOptions,
) -> Result<Vec<Partition>, RingError> {
    let mesh = &body.mesh;
    let Some((lo, hi)) = mesh.bounds() else {
        return Ok(Vec::new());
    };
    let height = hi.y - lo.y;
    let margin = options.margin_fraction * height;
    let eps = height * 2e-3;
    let tri_range: Vec<(f64, f64)> = (0..mesh.triangles.len())
        .map(|t| {
            let [a, b, c] = mesh.corners(t);
            (a.y.min(b.y).min(c.y), a.y.max(b.y).max(c.y))
        })
        .collect();
    let mut out = Vec::new();
    for (id, lower_y, upper_y) in partition_bounds(landmarks, lo.y, hi.y) {
        let triangles: Vec<u32> = tri_range
            .iter()
            .enumerate()
            .filter(|(_, (a, b))| *b >= lower_y - margin && *a <= upper_y + margin)
            .map(|(t, _)| t as u32)
            .collect();
        // Display rings at the bounds; the floor and the head top have no section, so A
        // starts at the ankles and G ends at the narrowest neck.
        let (lower_ring_y, lower_pick) = match id {
            PartitionId::A => (landmarks.height(LandmarkKind::Ankle), RingPick::Legs),
            PartitionId::B => (lower_y + eps, RingPick::Torso),
            _ => (lower_y, RingPick::Torso),
        };
        let (upper_ring_y, upper_pick) = match id {
            PartitionId::A => (upper_y - eps, RingPick::Legs),
            PartitionId::E => (upper_y - eps, RingPick::Torso),
            PartitionId::G => (landmarks.height(LandmarkKind::Neck), RingPick::Torso),
            _ => (upper_y, RingPick::Torso),
        };
        let name = |which: &str| format!("{}.{which}", id.letter());
        let mut rings = pick_rings(body, landmarks, (&name("lower"), None), lower_ring_y, lower_pick)?;
        rings.extend(pick_rings(
            body,
            landmarks,
            (&name("upper"), None),
            upper_ring_y,
            upper_pick,
        )?);
        out.push(Partition {
            id,
            lower_y,
            upper_y,
            method: id.method(),
            response: id.response(),
            triangle_count: triangles.len(),
            triangles,
            rings,
        });
    }
    Ok(out)
}
