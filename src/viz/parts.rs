//! Garment meshes logged part by part: consecutive patches grouped into parts of at least
//! [`PART_FACES`] faces, one entity per part (`<root>/p007`, named by its first patch), its
//! edges likewise, and at each step only the parts, and of a part the fields, that differ
//! from what the recording shows at that entity already (see
//! [`OrderedRecording::log_part`]). A drag re-surfaces some patches and collides fewer; the
//! rest of the garment is not sent again, and the viewer, which shows the latest data of
//! each entity, still shows the whole garment.
//!
//! How a mesh is split ([`Layout`]: its parts, their vertices and faces, its edges shared
//! out and drawn as few polylines) depends on its faces, their patches and its edges alone;
//! the logger keeps the last layout of each mesh and makes a new one only when these
//! change, so a drag that moves vertices only gathers their points again.
//!
//! A part is a trade: each entity costs a chunk of its own (about 90 us to encode and write
//! on one core, whatever its size: `cargo bench --bench logging`), and data is sent again a part at a time.

use std::collections::BTreeSet;
use std::sync::{Arc, OnceLock};

use glam::DVec3;
use rerun::{LineStrips3D, Mesh3D, Points3D};

use super::columns::{strips, triangles, vec3s};
use super::draw::{Walks, edge_walks, f32s};
use super::recording::{OrderedRecording, Words};
use crate::session::SinkError;

/// The fewest faces a part has by default (but the last, which takes what is left): the
/// patches are grouped in order until they have as many ([`super::LogOptions::part_faces`]).
pub(super) const PART_FACES: usize = 4096;

/// The faces of one part, its vertices numbered in the order its faces meet them.
pub(super) struct Part {
    /// The part's index.
    pub part: u32,
    /// The mesh's index of each of the part's vertices.
    pub vertices: Vec<u32>,
    /// The part's faces, in the mesh's order, in the part's numbering, three words each
    /// (shared with every step that logs the part in this layout).
    pub triangles: Words,
}

/// The part of each face: consecutive patches (by index) grouped until a part has
/// `min_faces` faces (a last part short of it joins the one before); with the entity name
/// of each part, `p` and its first patch.
pub(super) fn parts_of(face_patch: &[u32], min_faces: usize) -> (Vec<u32>, Vec<String>) {
    let patches = face_patch.iter().max().map_or(0, |&p| p as usize + 1);
    let mut faces = vec![0usize; patches];
    for &p in face_patch {
        faces[p as usize] += 1;
    }
    let mut part_of = vec![0u32; patches];
    let mut names = Vec::new();
    let mut size = min_faces;
    for p in 0..patches {
        if size >= min_faces && faces[p] > 0 {
            names.push(format!("p{p:03}"));
            size = 0;
        }
        part_of[p] = names.len().saturating_sub(1) as u32;
        size += faces[p];
    }
    if size < min_faces && names.len() > 1 {
        names.pop();
        let last = names.len() as u32;
        for k in &mut part_of {
            *k = (*k).min(last - 1);
        }
    }
    (face_patch.iter().map(|&p| part_of[p as usize]).collect(), names)
}

/// The indices `0..n` grouped by `label` (counting sort, each group in index order), with
/// where each group starts (`start[l]..start[l + 1]`).
fn grouped(labels: impl Iterator<Item = usize> + Clone, groups: usize) -> (Vec<usize>, Vec<u32>) {
    let mut start = vec![0usize; groups + 1];
    for l in labels.clone() {
        start[l + 1] += 1;
    }
    for g in 0..groups {
        start[g + 1] += start[g];
    }
    let mut fill = start.clone();
    let mut order = vec![0u32; start[groups]];
    for (i, l) in labels.enumerate() {
        order[fill[l]] = i as u32;
        fill[l] += 1;
    }
    (start, order)
}

/// Renumbers `items` (lists of mesh vertices) into a part's own numbering: the part's
/// vertices in the order met, returned, and the items in it, written to `words` (`N` words
/// each). `local` is all `u32::MAX` on entry and on return.
fn renumber<const N: usize>(
    items: impl Iterator<Item = [u32; N]>,
    local: &mut [u32],
    words: &mut Vec<u32>,
) -> Vec<u32> {
    let mut vertices = Vec::new();
    words.clear();
    for item in items {
        for v in item {
            let l = &mut local[v as usize];
            if *l == u32::MAX {
                *l = vertices.len() as u32;
                vertices.push(v);
            }
            words.push(*l);
        }
    }
    for &v in &vertices {
        local[v as usize] = u32::MAX;
    }
    vertices
}

/// `words` as a part's shared words: `old`'s when they are the same (no new list), else new.
fn shared_or_new(words: &[u32], old: Option<&Words>) -> Words {
    match old {
        Some(o) if o.as_slice() == words => Arc::clone(o),
        _ => Arc::new(words.to_vec()),
    }
}

/// The mesh of `vertex_count` vertices and `triangles` split by `face_part` into
/// `parts` parts, those with faces, in order; a part whose faces, in its own numbering, are
/// those `old` gives for it shares them.
pub(super) fn split<'a>(
    vertex_count: usize,
    triangles: &[[u32; 3]],
    (face_part, parts): (&[u32], usize),
    old: impl Fn(u32) -> Option<&'a Words>,
) -> Vec<Part> {
    let (start, order) = grouped(face_part.iter().map(|&p| p as usize), parts);
    let mut local = vec![u32::MAX; vertex_count];
    let mut words = Vec::new();
    (0..parts)
        .filter(|&p| start[p] < start[p + 1])
        .map(|p| {
            let faces = order[start[p]..start[p + 1]].iter().map(|&f| triangles[f as usize]);
            let vertices = renumber(faces, &mut local, &mut words);
            Part {
                part: p as u32,
                vertices,
                triangles: shared_or_new(&words, old(p as u32)),
            }
        })
        .collect()
}

/// The mesh's `edges` shared out among the `parts` parts, each edge to one: the later of
/// its ends' first parts (the lowest part of a face around the vertex), so that an edge
/// inside a part goes to that part and one along a seam to one side of it. A part whose
/// edges, in its own numbering, are those of the edge part `old` gives for it shares them
/// and their walks.
pub(super) fn split_edges<'a>(
    vertex_count: usize,
    triangles: &[[u32; 3]],
    (face_part, parts): (&[u32], usize),
    edges: &[[u32; 2]],
    old: impl Fn(u32) -> Option<&'a EdgePart>,
) -> Vec<EdgePart> {
    if parts == 0 {
        return Vec::new();
    }
    let mut first = vec![u32::MAX; vertex_count];
    for (t, &p) in triangles.iter().zip(face_part) {
        for &v in t {
            first[v as usize] = first[v as usize].min(p);
        }
    }
    let owner: Vec<u32> = (edges.iter())
        .map(|&[a, b]| first[a as usize].max(first[b as usize]).min(parts as u32 - 1))
        .collect();
    let (start, order) = grouped(owner.iter().map(|&p| p as usize), parts);
    let mut local = vec![u32::MAX; vertex_count];
    let mut words = Vec::new();
    (0..parts)
        .filter(|&p| start[p] < start[p + 1])
        .map(|p| {
            let items = order[start[p]..start[p + 1]].iter().map(|&e| edges[e as usize]);
            let vertices = renumber(items, &mut local, &mut words);
            match old(p as u32).filter(|o| o.edges.as_slice() == words.as_slice()) {
                Some(o) => EdgePart {
                    part: p as u32,
                    walks: Arc::clone(&o.walks),
                    vertices,
                    edges: Arc::clone(&o.edges),
                },
                None => EdgePart {
                    part: p as u32,
                    walks: Arc::new(OnceLock::new()),
                    vertices,
                    edges: Arc::new(words.clone()),
                },
            }
        })
        .collect()
}

/// The edges given to one part, in their own numbering.
pub(super) struct EdgePart {
    /// The part's index.
    pub part: u32,
    /// The mesh's index of each vertex the edges use.
    pub vertices: Vec<u32>,
    /// The edges, in the part's numbering, two words each (shared like a part's faces).
    pub edges: Words,
    /// The edges as few polylines ([`super::draw::edge_paths`]), in the part's numbering,
    /// found the first time the part is sent (shared with a later layout's part of the same
    /// edges).
    walks: Arc<OnceLock<Walks>>,
}

impl EdgePart {
    /// The edges as few polylines (Rerun's strips, `descriptor`) through `points` (the
    /// words of the part's vertices' points).
    pub fn paths(&self, descriptor: rerun::ComponentDescriptor, points: &[u32]) -> rerun::SerializedComponentBatch {
        let walks = (self.walks).get_or_init(|| edge_walks(self.vertices.len(), self.edges.as_chunks::<2>().0));
        strips(descriptor, (walks.start(), walks.vertices()), points)
    }
}

/// The points `at` of `vertices`, as words (their bits).
fn gathered_words(at: &[[f32; 3]], vertices: &[u32]) -> Words {
    Arc::new(
        vertices
            .iter()
            .flat_map(|&v| at[v as usize].map(f32::to_bits))
            .collect(),
    )
}

fn color_word([r, g, b]: [u8; 3]) -> u32 {
    u32::from_le_bytes([r, g, b, 0])
}

/// The smooth vertex normals of the whole mesh (so that a part's shading runs on across
/// its seams), as Rerun takes them; summed in `sums` (see
/// [`crate::mesh::trimesh::vertex_normals_into`]).
pub(super) fn f32_normals(positions: &[DVec3], triangles: &[[u32; 3]], sums: &mut Vec<DVec3>) -> Vec<[f32; 3]> {
    crate::mesh::trimesh::vertex_normals_into(positions, triangles, sums);
    sums.iter().map(|n| n.as_vec3().to_array()).collect()
}

/// How a mesh is split into parts, with its edges: a function of its faces, their patches
/// and its edges alone, kept from step to step while they stay the same (a drag moves
/// vertices, not faces).
pub(super) struct Layout {
    /// The vertex count, faces, their patches, the edges and the fewest faces of a part it
    /// was made for.
    vertex_count: usize,
    triangles: Vec<[u32; 3]>,
    face_patch: Arc<Vec<u32>>,
    edges: Arc<Vec<[u32; 2]>>,
    part_faces: usize,
    /// The entity name of each part.
    pub names: Vec<String>,
    /// The parts with faces.
    pub parts: Vec<Part>,
    /// The edges shared out among the parts.
    pub edge_parts: Vec<EdgePart>,
}

impl Layout {
    /// The mesh of `vertex_count` vertices and `triangles` (of patches `face_patch`) split into
    /// parts of whole patches of `part_faces` faces or more, its `edges` shared out among them.
    /// A part of the same name as one of `before` (the mesh's last layout) with the same faces,
    /// or edges, in its own numbering shares them with it, and its edges' walks: a new
    /// refinement of a few patches leaves the other parts as they were, only renumbered.
    pub fn new(
        vertex_count: usize,
        triangles: &[[u32; 3]],
        (face_patch, edges): (&Arc<Vec<u32>>, &Arc<Vec<[u32; 2]>>),
        (part_faces, before): (usize, Option<&Self>),
    ) -> Self {
        let (face_part, names) = parts_of(face_patch, part_faces.max(1));
        let named = |part: u32| names[part as usize].as_str();
        let parts = split(vertex_count, triangles, (&face_part, names.len()), |p| {
            before.and_then(|b| b.part_named(named(p))).map(|o| &o.triangles)
        });
        let edge_parts = split_edges(vertex_count, triangles, (&face_part, names.len()), edges, |p| {
            before.and_then(|b| b.edge_part_named(named(p)))
        });
        Self {
            vertex_count,
            triangles: triangles.to_vec(),
            face_patch: Arc::clone(face_patch),
            edges: Arc::clone(edges),
            part_faces,
            names,
            parts,
            edge_parts,
        }
    }

    /// Its part named `name`, if any.
    fn part_named(&self, name: &str) -> Option<&Part> {
        self.parts.iter().find(|p| self.names[p.part as usize] == name)
    }

    /// Its edge part named `name`, if any.
    fn edge_part_named(&self, name: &str) -> Option<&EdgePart> {
        self.edge_parts.iter().find(|p| self.names[p.part as usize] == name)
    }

    /// Whether it is the layout of this mesh (the faces' patches and the edges compared
    /// only when they are not the very lists it was made for).
    pub fn fits(
        &self,
        (vertex_count, triangles): (usize, &[[u32; 3]]),
        (face_patch, edges): (&Arc<Vec<u32>>, &Arc<Vec<[u32; 2]>>),
        part_faces: usize,
    ) -> bool {
        self.vertex_count == vertex_count
            && self.part_faces == part_faces
            && self.triangles == triangles
            && (Arc::ptr_eq(&self.face_patch, face_patch) || self.face_patch == *face_patch)
            && (Arc::ptr_eq(&self.edges, edges) || self.edges == *edges)
    }
}

/// A mesh as it is logged: its points and smooth normals as Rerun takes them, and its
/// layout.
pub(super) struct Parted {
    /// Positions.
    pub points: Vec<[f32; 3]>,
    /// Smooth vertex normals of the whole mesh.
    pub normals: Vec<[f32; 3]>,
    /// How it is split into parts.
    pub layout: Arc<Layout>,
}

impl Parted {
    /// The mesh `layout` was made for, at `positions` (its normals summed in `sums`).
    pub fn of(positions: &[DVec3], layout: Arc<Layout>, sums: &mut Vec<DVec3>) -> Self {
        Self {
            points: f32s(positions),
            normals: f32_normals(positions, &layout.triangles, sums),
            layout,
        }
    }
}

/// The words that make each field of a part, by field name.
type Fields = Vec<(&'static str, Words)>;

/// Logs each `(name, fields, build)` at `<root>/<name>` through
/// [`OrderedRecording::log_part`], and clears the entities under `root` that are not among
/// them (the parts a mesh no longer has). Returns how many were sent.
fn log_named<AS, B>(
    rec: &OrderedRecording,
    root: &str,
    items: impl Iterator<Item = (String, Fields, B)>,
) -> Result<usize, SinkError>
where
    AS: rerun::AsComponents,
    B: FnOnce(&[bool]) -> AS,
{
    let mut logged = 0;
    let mut names = BTreeSet::new();
    for (name, fields, build) in items {
        logged += usize::from(rec.log_part(format!("{root}/{name}"), fields, build)?);
        names.insert(name);
    }
    rec.clear_others(root, &names)?;
    Ok(logged)
}

/// Logs each part as a mesh at `<root>/<part name>`, those the entity shows already left
/// out (and of the others, the fields it shows: a moved patch sends its positions and
/// normals, not its triangles), and clears the parts under `root` the mesh no longer has.
/// Returns how many were logged.
pub(super) fn log_mesh_parts(
    rec: &OrderedRecording,
    root: &str,
    parted: &Parted,
    colors: &[[u8; 3]],
) -> Result<usize, SinkError> {
    let layout = &parted.layout;
    let items = layout.parts.iter().map(|part| {
        let points = gathered_words(&parted.points, &part.vertices);
        let normals = gathered_words(&parted.normals, &part.vertices);
        let vertex_colors: Vec<u32> = part.vertices.iter().map(|&v| color_word(colors[v as usize])).collect();
        let fields = vec![
            ("positions", Arc::clone(&points)),
            ("normals", Arc::clone(&normals)),
            ("triangles", Arc::clone(&part.triangles)),
            ("colors", Arc::new(vertex_colors)),
        ];
        let build = move |changed: &[bool]| {
            let mut m = Mesh3D::update_fields();
            if changed[0] {
                m.vertex_positions = Some(vec3s(Mesh3D::descriptor_vertex_positions(), &points));
            }
            if changed[1] {
                m.vertex_normals = Some(vec3s(Mesh3D::descriptor_vertex_normals(), &normals));
            }
            if changed[2] {
                m.triangle_indices = Some(triangles(Mesh3D::descriptor_triangle_indices(), &part.triangles));
            }
            if changed[3] {
                let rgb = part.vertices.iter().map(|&v| colors[v as usize]);
                m.vertex_colors = Some(super::columns::colors(Mesh3D::descriptor_vertex_colors(), rgb));
            }
            m
        };
        (layout.names[part.part as usize].clone(), fields, build)
    });
    log_named(rec, root, items)
}

/// Logs each edge part as polylines at `<root>/<part name>` (radius and colour as given),
/// those the entity shows already left out, and clears the parts the mesh no longer has.
/// Returns how many were logged.
pub(super) fn log_edge_parts(
    rec: &OrderedRecording,
    root: &str,
    parted: &Parted,
    (radius, color): (f32, [u8; 3]),
) -> Result<usize, SinkError> {
    let layout = &parted.layout;
    let items = layout.edge_parts.iter().map(|part| {
        let mine = gathered_words(&parted.points, &part.vertices);
        let fields = vec![
            ("points", Arc::clone(&mine)),
            ("edges", Arc::clone(&part.edges)),
            ("style", Arc::new(vec![radius.to_bits(), color_word(color)])),
        ];
        let build = move |changed: &[bool]| {
            let mut strips = LineStrips3D::update_fields();
            if changed[0] || changed[1] {
                strips.strips = Some(part.paths(LineStrips3D::descriptor_strips(), &mine));
            }
            if changed[2] {
                strips = strips.with_radii([radius]).with_colors([color]);
            }
            strips
        };
        (layout.names[part.part as usize].clone(), fields, build)
    });
    log_named(rec, root, items)
}

/// Logs the points of each part at or after vertex `from` (M1's new vertices) at
/// `<root>/<part name>`, as [`log_mesh_parts`] does its meshes.
pub(super) fn log_point_parts(
    rec: &OrderedRecording,
    root: &str,
    (parted, from): (&Parted, usize),
    (radius, color): (f32, [u8; 3]),
) -> Result<usize, SinkError> {
    let layout = &parted.layout;
    let items = layout.parts.iter().filter_map(|part| {
        let mine: Vec<u32> = (part.vertices.iter())
            .filter(|&&v| v as usize >= from)
            .flat_map(|&v| parted.points[v as usize].map(f32::to_bits))
            .collect();
        if mine.is_empty() {
            return None;
        }
        let mine = Arc::new(mine);
        let fields = vec![
            ("positions", Arc::clone(&mine)),
            ("style", Arc::new(vec![radius.to_bits(), color_word(color)])),
        ];
        let build = move |changed: &[bool]| {
            let mut p = Points3D::update_fields();
            if changed[0] {
                p.positions = Some(vec3s(Points3D::descriptor_positions(), &mine));
            }
            if changed[1] {
                p = p.with_radii([radius]).with_colors([color]);
            }
            p
        };
        Some((layout.names[part.part as usize].clone(), fields, build))
    });
    log_named(rec, root, items)
}
