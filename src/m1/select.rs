//! Which patches of M0 M1 refines (\[collide\] section 3.2, the four rules), each a
//! documented threshold, and which rule selected which patch.
//!
//! 1. **stretch**: an edge of the patch is longer than [`SelectOptions::stretch`] times its
//!    length in the garment as first built (the template's standard size on this body):
//!    the garment has been stretched there and the mesh has thinned.
//! 2. **angle**: two adjacent triangles of the patch have normals more than
//!    [`SelectOptions::angle_deg`] apart: a fold or a sharp feature.
//! 3. **edges**: the patch's longest edge is more than [`SelectOptions::long_edge`] times
//!    its mean edge, or its shortest less than [`SelectOptions::short_edge`] times it: the
//!    edge lengths are very uneven.
//! 4. **body**: an edge of the patch is longer than [`SelectOptions::body_edge`] times the
//!    body's edge beneath it (the mean edge of the body triangle nearest each end, averaged
//!    over the two ends): the garment is coarser than the body beneath it, so its edges can
//!    cut through the body's bumps.

use std::collections::BTreeMap;
use std::sync::Arc;

use glam::DVec3;

use crate::collision::quality::Measured;
use crate::mesh::TriMesh;
use crate::mesh::topology::sorted_edges;

/// A selection rule.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Rule {
    /// Stretched past a ratio of the standard size.
    Stretch,
    /// Normals of adjacent triangles too far apart.
    Angle,
    /// Uneven edge lengths.
    Edges,
    /// Edges long against the body's.
    Body,
}

impl Rule {
    /// Every rule, in the order they are tried.
    pub const ALL: [Self; 4] = [Self::Stretch, Self::Angle, Self::Edges, Self::Body];

    /// Name in sessions and metrics.
    pub fn name(self) -> &'static str {
        match self {
            Self::Stretch => "stretch",
            Self::Angle => "angle",
            Self::Edges => "edges",
            Self::Body => "body",
        }
    }

    /// From a session name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|r| r.name() == name)
    }
}

/// Thresholds of the rules (dimensionless: ratios and an angle, the same on any body).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct SelectOptions {
    /// The rules in use (default: all four).
    pub rules: Vec<Rule>,
    /// Rule 1: an edge longer than this times its standard length (default 1.2).
    pub stretch: f64,
    /// Rule 2: adjacent normals further apart than this, degrees (default 30).
    pub angle_deg: f64,
    /// Rule 3: longest edge over the patch's mean edge (default 2.0).
    pub long_edge: f64,
    /// Rule 3: shortest edge over the patch's mean edge (default 0.25).
    pub short_edge: f64,
    /// Rule 4: a garment edge over the mean edge of the body triangle beneath it (default
    /// 2.0).
    pub body_edge: f64,
}

impl Default for SelectOptions {
    fn default() -> Self {
        Self {
            rules: Rule::ALL.to_vec(),
            stretch: 1.2,
            angle_deg: 30.0,
            long_edge: 2.0,
            short_edge: 0.25,
            body_edge: 2.0,
        }
    }
}

/// The patches selected, each with the rules that selected it (in [`Rule::ALL`] order).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Selection {
    /// Per patch: the rules that fired (empty: not refined).
    pub rules: Vec<Vec<Rule>>,
}

impl Selection {
    /// Whether each patch is refined.
    pub fn refined(&self) -> Vec<bool> {
        self.rules.iter().map(|r| !r.is_empty()).collect()
    }

    /// Refined patches.
    pub fn count(&self) -> usize {
        self.rules.iter().filter(|r| !r.is_empty()).count()
    }

    /// Patches each rule selected (a patch may count under several rules).
    pub fn by_rule(&self) -> BTreeMap<&'static str, usize> {
        Rule::ALL
            .into_iter()
            .map(|rule| (rule.name(), self.rules.iter().filter(|r| r.contains(&rule)).count()))
            .filter(|(_, n)| *n > 0)
            .collect()
    }

    /// Every patch, selected or not.
    pub fn all(patches: usize) -> Self {
        Self {
            rules: vec![Rule::ALL.to_vec(); patches],
        }
    }
}

/// What the rules read: M0 (after collision), the patch of each face, its undirected
/// edges, and M0 as first built (same topology) for the stretch rule.
pub struct SelectInput<'a> {
    /// M0 now.
    pub mesh: &'a TriMesh,
    /// Patch of each face.
    pub face_patch: &'a [u32],
    /// Number of patches.
    pub patches: usize,
    /// M0's vertex positions as first built (the standard size), if known; not read when
    /// M0 has since another vertex count (an edit that changed its layout).
    pub standard: Option<&'a [DVec3]>,
    /// The vertices' distances M0's quality check measured, if kept: rule 4 reads the
    /// nearest body triangle of a vertex still where it was measured instead of searching.
    pub measured: Option<&'a Measured>,
    /// M0's edges with their faces, if kept from an earlier step (read only when they were
    /// found in the same faces as `mesh`'s).
    pub edges: Option<&'a Arc<EdgeFaces>>,
}

/// M0's undirected edges, each with its faces ([`sorted_edges`]), and the faces they were
/// found in: kept from step to step while M0's faces stay the same (a drag moves vertices,
/// not faces).
#[derive(Debug)]
pub struct EdgeFaces {
    /// The faces.
    triangles: Vec<[u32; 3]>,
    /// Their edges, as [`sorted_edges`] gives them.
    records: Vec<(u32, u32, u32, u8)>,
}

impl EdgeFaces {
    /// `previous` when it was found in `mesh`'s faces, or found anew.
    pub fn of(mesh: &TriMesh, previous: Option<&Arc<Self>>) -> Arc<Self> {
        match previous {
            Some(e) if e.triangles == mesh.triangles => Arc::clone(e),
            _ => Arc::new(Self {
                triangles: mesh.triangles.clone(),
                records: sorted_edges(mesh),
            }),
        }
    }

    /// The faces it was found in.
    pub(crate) fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// Its edge records `(min vertex, max vertex, face, local edge)`, sorted.
    pub(crate) fn records(&self) -> &[(u32, u32, u32, u8)] {
        &self.records
    }
}
