//! The families of stages: the data each kind of step hands on (borrowed), and the names
//! of their parts.

use crate::body::{BodyMesh, BodyRing, Landmarks, Partition};
use crate::collision::{BodyIndex, Collision, GarmentMesh, VerifyReport};
use crate::constraint::{ConstraintNet, Edit, Solution};
use crate::garment::Framework;
use crate::geom::SectionLoop;
use crate::m1::{M1, M1Collision, StoredCut};

/// The NURBS parts of a scene.
#[derive(Clone, Copy, Debug)]
pub struct NurbsStage<'a> {
    /// Every part, where it stands after the step.
    pub parts: &'a [crate::nurbs::NurbsPart],
    /// The part the step added or moved.
    pub moved: &'a str,
    /// What that part comes within the threshold of (the body, other parts).
    pub contacts: &'a [crate::nurbs::Contact],
    /// Refused: the step left the part where it was, and why.
    pub refused: Option<&'a str>,
}

/// The scene's body stages, in the order they are emitted.
#[derive(Clone, Copy, Debug)]
#[non_exhaustive]
pub enum BodyStage<'a> {
    /// The body mesh, loaded and validated.
    Mesh(&'a BodyMesh),
    /// Its landmarks.
    Landmarks(&'a BodyMesh, &'a Landmarks),
    /// The rings cut at the landmarks.
    Rings(&'a [BodyRing]),
    /// The partitions A-G.
    Partitions(&'a BodyMesh, &'a [Partition]),
}

/// A horizontal section of the body (the `section` step).
#[derive(Clone, Copy, Debug)]
pub struct SectionCut<'a> {
    /// The name given in the session.
    pub name: &'a str,
    /// Height of the plane, m (world frame, y up).
    pub y: f64,
    /// The loops the plane cuts.
    pub loops: &'a [SectionLoop],
}

/// The garment stages.
#[derive(Clone, Copy, Debug)]
#[non_exhaustive]
pub enum GarmentStage<'a> {
    /// One part of the framework, as solved or re-surfaced.
    Part(&'a Framework, GarmentPart),
    /// A dimension edit: the framework before and after.
    Edit {
        /// The dimension changed.
        name: &'a str,
        /// Before.
        before: &'a Framework,
        /// After.
        after: &'a Framework,
    },
    /// A dimension change that cannot be honoured (out of its range, a girth the body
    /// cannot have, a drag that cannot be made again after it): refused, the garment is as
    /// before the step.
    Refused {
        /// The dimension.
        name: &'a str,
        /// The value asked for.
        value: f64,
        /// Why, naming the limit.
        message: &'a str,
    },
    /// A cut line that cannot be drawn (its plane misses the garment): refused, the garment
    /// is as before the step.
    CutRefused {
        /// The cut line's name.
        name: &'a str,
        /// Why.
        message: &'a str,
    },
    /// `undo`: the garment is back to this state (with its constraint network, once one was
    /// built).
    Undone {
        /// The framework restored.
        framework: &'a Framework,
        /// Its constraint network.
        net: Option<&'a ConstraintNet>,
    },
}

/// The parts of a garment, in the order they are emitted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GarmentPart {
    /// The section planes.
    Planes,
    /// Every ring at one sub-step.
    Rings(RingStep),
    /// Open curves, contours, seams (and the loose-fit straightening).
    Curves,
    /// The Coons patches.
    Patches,
    /// The stitched mesh M0.
    Mesh,
}

/// A ring sub-step (\[frame\] section 2.2).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RingStep {
    /// The body section.
    Raw,
    /// Convexified.
    Convex,
    /// Resampled at equal chords.
    Resampled,
    /// Eased.
    Eased,
    /// Spline fitted through the control points and resampled.
    Fitted,
}

impl RingStep {
    /// In order.
    pub const ALL: [Self; 5] = [Self::Raw, Self::Convex, Self::Resampled, Self::Eased, Self::Fitted];

    /// Short name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Raw => "raw",
            Self::Convex => "convex",
            Self::Resampled => "resampled",
            Self::Eased => "eased",
            Self::Fitted => "fitted",
        }
    }
}

impl GarmentPart {
    /// Every part in emission order.
    pub fn all() -> Vec<Self> {
        let mut out = vec![Self::Planes];
        out.extend(RingStep::ALL.map(Self::Rings));
        out.extend([Self::Curves, Self::Patches, Self::Mesh]);
        out
    }

    /// The parts an edit re-surfaces (the rings' sub-steps and planes stay as built).
    pub const RESURFACED: [Self; 3] = [Self::Curves, Self::Patches, Self::Mesh];

    /// Stage name.
    pub fn stage_name(self) -> &'static str {
        match self {
            Self::Planes => "garment.planes",
            Self::Rings(RingStep::Raw) => "garment.rings.raw",
            Self::Rings(RingStep::Convex) => "garment.rings.convex",
            Self::Rings(RingStep::Resampled) => "garment.rings.resampled",
            Self::Rings(RingStep::Eased) => "garment.rings.eased",
            Self::Rings(RingStep::Fitted) => "garment.rings.fitted",
            Self::Curves => "garment.curves",
            Self::Patches => "garment.patches",
            Self::Mesh => "garment.m0",
        }
    }
}

/// A collision stage: the step's collision, the body index it ran against, and which part.
#[derive(Clone, Copy, Debug)]
pub struct CollisionStage<'a> {
    /// M0 as collided, the result, the ground-truth check.
    pub outcome: &'a CollisionOutcome,
    /// The body index (partitions, slices).
    pub index: &'a BodyIndex,
    /// Detection or response.
    pub part: CollisionPart,
}

/// The parts of a collision, in the order they are emitted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CollisionPart {
    /// Detection: the penetrating vertices by partition.
    Detect,
    /// Response: the moved vertices and M0 after it.
    Respond,
}

impl CollisionPart {
    /// Both parts, in emission order.
    pub const ALL: [Self; 2] = [Self::Detect, Self::Respond];

    /// Stage name.
    pub fn stage_name(self) -> &'static str {
        match self {
            Self::Detect => "collision.detect",
            Self::Respond => "collision.response",
        }
    }
}

/// A step's collision: M0 as collided, the result, and the ground-truth check.
#[derive(Clone, Debug)]
pub struct CollisionOutcome {
    /// The garment mesh before response, with its roles.
    pub garment: GarmentMesh,
    /// Detection, response, quality.
    pub collision: Collision,
    /// With `--verify`: the brute-force check.
    pub verify: Option<VerifyReport>,
    /// The garment's name: its template's, or the one `garment mesh` gave (file names,
    /// the log).
    pub name: String,
    /// The file the garment was read from (`garment mesh`): what `--export` writes back
    /// with the file's own structure. `None` for a garment built from a template.
    pub source: Option<std::sync::Arc<crate::import::ImportedGarment>>,
}

/// M1 of a step: built over the step's collided M0, collided where it differs from M0, with
/// the cut lines rebuilt on it.
#[derive(Clone, Copy, Debug)]
pub struct M1Stage<'a> {
    /// M1 and its collision.
    pub outcome: &'a M1Outcome,
    /// M0's collision the M1 was built on.
    pub m0: &'a CollisionOutcome,
}

/// The pattern pieces of a step's garment (or why there are none).
#[derive(Clone, Copy, Debug)]
pub struct PatternStage<'a> {
    /// The pattern, or why it could not be made.
    pub result: &'a Result<crate::pattern::Pattern, crate::pattern::PatternError>,
    /// The garment's name.
    pub garment: &'a str,
}

/// M1 and what became of it.
#[derive(Clone, Debug)]
pub struct M1Outcome {
    /// M1 before its collision, with the selection (shared with the shape the next step
    /// may keep).
    pub m1: std::sync::Arc<M1>,
    /// Its collision (positions after response, quality).
    pub collision: M1Collision,
    /// The cut lines as stored on M0.
    pub stored: Vec<StoredCut>,
    /// Each cut line rebuilt on this M1 (pieces of positions, closed or not).
    pub cuts: Vec<Vec<(Vec<glam::DVec3>, bool)>>,
    /// Each cut line's stored points placed on M0 (after its collision).
    pub cuts_on_m0: Vec<Vec<(Vec<glam::DVec3>, bool)>>,
}

/// A sculpt of the garment.
#[derive(Clone, Copy, Debug)]
pub struct SculptStage<'a> {
    /// The sculpt made (or attempted, when refused); `None`: the garment has no sculpt any
    /// more (an undo took it back).
    pub outcome: Option<&'a SculptOutcome>,
    /// Refused: the garment stays as it was, and why.
    pub refused: Option<&'a str>,
}

/// A sculpt and what became of it.
#[derive(Clone, Debug)]
pub struct SculptOutcome {
    /// The drag.
    pub drag: crate::sculpt::Drag,
    /// The mesh it was made on: `M0`, `M1` or `sculpt` (the last sculpt's result).
    pub layer: &'static str,
    /// That mesh (collided).
    pub base: crate::mesh::TriMesh,
    /// The drag and the adaptive refinement.
    pub sculpt: crate::sculpt::Sculpt,
    /// The refinement's collision with the body (positions after the response).
    pub collision: M1Collision,
    /// Partition of each vertex of the result (for the next sculpt's collision).
    pub partition: Vec<usize>,
    /// Ring plane normal of each vertex of the result on a garment ring.
    pub ring_normal: Vec<Option<glam::DVec3>>,
    /// Sculpts made so far on this garment (this one included).
    pub count: usize,
}

impl SculptOutcome {
    /// One line for the log and the progress: what the drag moved, how the refinement
    /// went, and what the collision found and left.
    pub fn summary(&self) -> String {
        let s = &self.sculpt;
        let c = &self.collision;
        let d = &s.displacement;
        format!(
            "sculpt {} on {}: {} vertices moved ({} stopped at the body), {} region faces; epsilon {:.4} m, {} \
             level(s), active faces {:?}{}; {} -> {} faces; {} tested, {} inside before, {} moves; after: {} \
             inside, {} crossing edges",
            self.count,
            self.layer,
            d.offsets.len(),
            d.stopped,
            d.region.len(),
            s.epsilon,
            s.refined.levels.len(),
            s.refined.levels.iter().map(|l| l.active.len()).collect::<Vec<_>>(),
            if s.refined.limited {
                " (stopped at the level limit)"
            } else {
                ""
            },
            self.base.triangles.len(),
            s.refined.mesh.triangles.len(),
            c.tested,
            c.hits,
            c.responses.len(),
            c.quality.penetrating_vertices,
            c.quality.crossing_edges,
        )
    }

    /// The sculpted mesh after its collision.
    pub fn mesh(&self) -> crate::mesh::TriMesh {
        crate::mesh::TriMesh {
            positions: self.collision.positions.clone(),
            triangles: self.sculpt.refined.mesh.triangles.clone(),
        }
    }
}

/// The constraint-layer stages.
#[derive(Clone, Copy, Debug)]
#[non_exhaustive]
pub enum ConstraintStage<'a> {
    /// The constraint network of a garment as built.
    Network(&'a Framework, &'a ConstraintNet),
    /// An edit solved: the framework before, the solution (its framework is re-surfaced in
    /// the garment stages that follow).
    Solve {
        /// The edit.
        edit: &'a Edit,
        /// The network.
        net: &'a ConstraintNet,
        /// Before the edit.
        before: &'a Framework,
        /// The solve.
        solution: &'a Solution,
    },
    /// An edit was refused; the garment is as before the step.
    Refused {
        /// The edit.
        edit: &'a Edit,
        /// Why.
        message: &'a str,
    },
}

/// A garment worn over others, after its push out in front of them.
#[derive(Clone, Debug)]
pub struct Layered {
    /// Per garment under it, innermost first: the push of its M0 and of its latest mesh.
    pub pairs: Vec<LayerPair>,
    /// Its latest mesh (the last sculpt, else M1, else M0), facing away from the body,
    /// after the pushes.
    pub mesh: crate::mesh::TriMesh,
    /// Per vertex of that mesh, its signed gap in front of the garment right under it, m
    /// (NaN where the nearest point under it is on an opening).
    pub gaps: Vec<f64>,
    /// The garments under it, innermost first: their names and latest meshes (shown muted).
    pub under: Vec<(String, crate::mesh::TriMesh)>,
}

/// One garment under another and how the one over it was pushed.
#[derive(Clone, Debug, serde::Serialize)]
pub struct LayerPair {
    /// The garment under.
    #[serde(skip)]
    pub under: String,
    /// The push of M0 out in front of its M0: the certificate before and after.
    pub m0: crate::layers::PushReport,
    /// The push of the latest mesh out in front of its latest mesh, when either has one
    /// beyond M0.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub latest: Option<crate::layers::PushReport>,
}
