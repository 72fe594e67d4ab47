//! The selection's four rules ([`super::select`]) applied patch by patch, each patch's rules
//! kept from the step before while nothing they read has changed.
//!
//! Every rule of [`super::select`] that fires for a patch reads only the patch's own edges
//! (an edge between two patches is the edge of both): their lengths, their lengths as first
//! built, the body's mean edge beneath their ends, and the normals of the patch's faces. So
//! a patch's rules are a function of the positions of its faces' corners and the body's
//! edge beneath them, with M0's faces, the patches, the standard size and the thresholds.
//! A drag re-surfaces some patches and leaves the rest where they were; [`SelectMemory`]
//! keeps, for the last step, those inputs and each patch's rules, and a patch none of whose
//! corners moved, and under none of which the body's edge changed, takes its rules from
//! there. The rest are measured as before; the same selection, bit for bit, as one made
//! whole (the same sums in the same order).

use std::sync::Arc;

use glam::DVec3;

use super::select::{EdgeFaces, Rule, SelectInput, SelectOptions, Selection};
use crate::body::index::BodyIndex;
use crate::collision::types::NO_TRIANGLE;
use crate::mesh::TriMesh;

/// What the rules of each patch read, fixed while M0's faces, its patches and its standard
/// size stay the same: M0's undirected edges and each patch's edges, faces and corners.
#[derive(Debug)]
struct SelectShape {
    /// M0's faces with their edges.
    edges: Arc<EdgeFaces>,
    /// The patch of each face.
    face_patch: Vec<u32>,
    /// M0 as first built, when its vertex count is M0's (the stretch rule reads it).
    standard: Option<Vec<DVec3>>,
    /// Each patch's edges, in order, an edge once for each time the patches of its faces,
    /// in face order with repeats next to each other merged, name the patch.
    patch_edges: Vec<Vec<PatchEdge>>,
    /// Each patch's faces, in order.
    patch_faces: Vec<Vec<u32>>,
    /// Each patch's corners (its faces' vertices), ascending.
    patch_vertices: Vec<Vec<u32>>,
}

impl SelectShape {
    /// The shape of `mesh` (whose faces `edges` holds) in `patches` patches.
    fn new(
        mesh: &TriMesh,
        edges: &Arc<EdgeFaces>,
        face_patch: &[u32],
        patches: usize,
        standard: Option<&[DVec3]>,
    ) -> Self {
        let records = edges.records();
        let standard = standard.filter(|s| s.len() == mesh.positions.len());
        let mut patch_faces = vec![Vec::new(); patches];
        let mut patch_vertices = vec![Vec::new(); patches];
        // Each face's place among its patch's faces.
        let mut place = Vec::with_capacity(face_patch.len());
        for (f, &p) in face_patch.iter().enumerate() {
            place.push(patch_faces[p as usize].len() as u32);
            patch_faces[p as usize].push(f as u32);
            patch_vertices[p as usize].extend(mesh.triangles[f]);
        }
        let mut patch_edges = vec![Vec::new(); patches];
        let mut of_edge: Vec<u32> = Vec::new();
        for group in records.chunk_by(|a, b| (a.0, a.1) == (b.0, b.1)) {
            let ends = [group[0].0, group[0].1];
            let pair = match group {
                [f, g] if face_patch[f.2 as usize] == face_patch[g.2 as usize] => {
                    [place[f.2 as usize], place[g.2 as usize]]
                }
                _ => [NO_PAIR; 2],
            };
            let was = standard.map_or(0.0, |s| s[ends[0] as usize].distance(s[ends[1] as usize]));
            of_edge.clear();
            of_edge.extend(group.iter().map(|r| face_patch[r.2 as usize]));
            of_edge.dedup();
            for &p in &of_edge {
                patch_edges[p as usize].push(PatchEdge { ends, pair, was });
            }
        }
        for v in &mut patch_vertices {
            v.sort_unstable();
            v.dedup();
        }
        Self {
            edges: Arc::clone(edges),
            face_patch: face_patch.to_vec(),
            standard: standard.map(<[DVec3]>::to_vec),
            patch_edges,
            patch_faces,
            patch_vertices,
        }
    }

    /// Whether it is the shape of `mesh` (faces held by `edges`) with these patches and
    /// this standard size.
    fn fits(&self, mesh: &TriMesh, edges: &Arc<EdgeFaces>, face_patch: &[u32], standard: Option<&[DVec3]>) -> bool {
        let standard = standard.filter(|s| s.len() == mesh.positions.len());
        (Arc::ptr_eq(&self.edges, edges) || self.edges.triangles() == mesh.triangles.as_slice())
            && self.face_patch == face_patch
            && self.standard.as_deref() == standard
    }

    /// The rules that fire for patch `p` of `mesh`, in [`Rule::ALL`] order. `beneath` is the
    /// body's mean edge beneath each vertex (read only when the body rule is on);
    /// `normals` is room for the unit normals of the patch's faces (in its order), filled here.
    fn rules_of(
        &self,
        p: usize,
        mesh: &TriMesh,
        beneath: &[f64],
        options: &SelectOptions,
        normals: &mut Vec<DVec3>,
    ) -> Vec<Rule> {
        let on = |r: Rule| options.rules.contains(&r);
        let mut fired: Vec<Rule> = Vec::new();
        let mut fire = |rule: Rule| {
            if !fired.contains(&rule) {
                fired.push(rule);
            }
        };
        if on(Rule::Angle) {
            normals.clear();
            normals.extend(
                self.patch_faces[p]
                    .iter()
                    .map(|&f| mesh.scaled_normal(f as usize).normalize_or_zero()),
            );
        }
        let cos_limit = options.angle_deg.to_radians().cos();
        let stretch = on(Rule::Stretch) && self.standard.is_some();
        let (mut sum, mut count, mut least, mut most) = (0.0f64, 0usize, f64::INFINITY, 0.0f64);
        for edge in &self.patch_edges[p] {
            let [a, b] = edge.ends.map(|v| v as usize);
            let len = mesh.positions[a].distance(mesh.positions[b]);
            (sum, count, least, most) = (sum + len, count + 1, least.min(len), most.max(len));
            if stretch && len > options.stretch * edge.was {
                fire(Rule::Stretch);
            }
            if on(Rule::Angle)
                && edge.pair[0] != NO_PAIR
                && let [f, g] = edge.pair.map(|f| f as usize)
                && normals[f].dot(normals[g]) < cos_limit
            {
                fire(Rule::Angle);
            }
            if on(Rule::Body) {
                let (ea, eb) = (beneath[a], beneath[b]);
                if ea > 0.0 && eb > 0.0 && len > options.body_edge * 0.5 * (ea + eb) {
                    fire(Rule::Body);
                }
            }
        }
        if on(Rule::Edges) && count > 0 {
            let mean = sum / count as f64;
            if most > options.long_edge * mean || least < options.short_edge * mean {
                fire(Rule::Edges);
            }
        }
        fired.sort_unstable();
        fired
    }
}

/// No pair of faces (an edge the angle rule does not read).
const NO_PAIR: u32 = u32::MAX;

/// One edge of a patch as the rules read it: its ends, its two faces (their places among
/// the patch's faces) when it has exactly two and both are in the patch (the angle rule's),
/// and its length as first built (0 without a standard size).
#[derive(Clone, Copy, Debug)]
struct PatchEdge {
    ends: [u32; 2],
    pair: [u32; 2],
    was: f64,
}

/// What the last selection read and found, patch by patch: kept from step to step (see the
/// module's docs).
#[derive(Debug)]
pub struct SelectMemory {
    /// The shape it was made on.
    shape: Arc<SelectShape>,
    /// The thresholds it used.
    options: SelectOptions,
    /// M0's positions it read.
    positions: Vec<DVec3>,
    /// The body's mean edge beneath each vertex it read (empty with the body rule off).
    beneath: Vec<f64>,
    /// Each patch's rules.
    rules: Vec<Vec<Rule>>,
}

impl SelectMemory {
    /// M0's faces with their edges, as this selection found them.
    pub fn edges(&self) -> &Arc<EdgeFaces> {
        &self.shape.edges
    }
}

/// What one selection reads: M0, its faces with their edges, the patch of each face, their
/// count, the standard size, and the body's mean edge beneath each vertex.
struct Reads<'a> {
    mesh: &'a TriMesh,
    edges: &'a Arc<EdgeFaces>,
    face_patch: &'a [u32],
    patches: usize,
    standard: Option<&'a [DVec3]>,
    beneath: Vec<f64>,
}

/// Each patch's rules, those of a patch `last` measured with the same corners, the same
/// body's edge beneath them and the same thresholds taken from it; with the memory for the
/// next step.
fn rules_keeping(
    reads: Reads<'_>,
    options: &SelectOptions,
    last: Option<&SelectMemory>,
) -> (Vec<Vec<Rule>>, SelectMemory) {
    let Reads {
        mesh,
        edges,
        face_patch,
        patches,
        standard,
        beneath,
    } = reads;
    let shape = match last {
        Some(m) if m.shape.fits(mesh, edges, face_patch, standard) && m.shape.patch_edges.len() == patches => {
            Arc::clone(&m.shape)
        }
        _ => Arc::new(SelectShape::new(mesh, edges, face_patch, patches, standard)),
    };
    let same = last.filter(|m| {
        Arc::ptr_eq(&m.shape, &shape)
            && m.options == *options
            && m.positions.len() == mesh.positions.len()
            && m.beneath.len() == beneath.len()
    });
    let unmoved = |v: u32| {
        same.is_some_and(|m| {
            let v = v as usize;
            bits(m.positions[v]) == bits(mesh.positions[v])
                && m.beneath.get(v).map(|b| b.to_bits()) == beneath.get(v).map(|b| b.to_bits())
        })
    };
    let mut normals = Vec::new();
    let rules = (0..patches)
        .map(|p| match same {
            Some(m) if shape.patch_vertices[p].iter().all(|&v| unmoved(v)) => m.rules[p].clone(),
            _ => shape.rules_of(p, mesh, &beneath, options, &mut normals),
        })
        .collect::<Vec<_>>();
    let memory = SelectMemory {
        shape,
        options: options.clone(),
        positions: mesh.positions.clone(),
        beneath,
        rules: rules.clone(),
    };
    (rules, memory)
}

/// Applies the rules.
pub fn select(input: &SelectInput<'_>, index: &BodyIndex, options: &SelectOptions) -> Selection {
    select_keeping(input, index, options, None).0
}

/// Applies the rules, taking from `last` (the memory of the step before) the rules of each
/// patch whose corners and the body's edge beneath them it read the same
/// (the module's docs); with the memory for the next step. The same selection as
/// [`select`], bit for bit.
pub fn select_keeping(
    input: &SelectInput<'_>,
    index: &BodyIndex,
    options: &SelectOptions,
    last: Option<&SelectMemory>,
) -> (Selection, SelectMemory) {
    let mesh = input.mesh;
    let edges = EdgeFaces::of(mesh, input.edges.or(last.map(SelectMemory::edges)));
    // Rule 4 reads, per garment vertex, the mean edge of the body triangle nearest it (the
    // body edge "beneath" a garment edge: the mean of its two ends'; 0 where no body is
    // within reach).
    let reach = 0.2 * index.height;
    let mean_edge = |t: u32| {
        let [a, b, c] = index.triangles[t as usize].map(|v| index.positions[v as usize]);
        (a.distance(b) + b.distance(c) + c.distance(a)) / 3.0
    };
    let beneath: Vec<f64> = if options.rules.contains(&Rule::Body) {
        crate::par::par_map(mesh.positions.len(), |v| {
            let p = mesh.positions[v];
            let nearest = match input.measured.and_then(|m| m.distance(v, p)) {
                Some(d) => (d.triangle != NO_TRIANGLE).then_some(d.triangle),
                None => index.nearest(p, reach).map(|near| near.triangle),
            };
            nearest.map_or(0.0, mean_edge)
        })
    } else {
        Vec::new()
    };
    let reads = Reads {
        mesh,
        edges: &edges,
        face_patch: input.face_patch,
        patches: input.patches,
        standard: input.standard,
        beneath,
    };
    let (rules, memory) = rules_keeping(reads, options, last);
    (Selection { rules }, memory)
}

/// A position's bits (so that -0.0 and 0.0 differ, and a NaN equals itself).
fn bits(p: DVec3) -> [u64; 3] {
    p.to_array().map(f64::to_bits)
}
