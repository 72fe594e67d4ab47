//! Triangle meshes: the mesh type, mesh files (OBJ, PLY, glTF) in and out, topology and
//! validation.

pub mod document;
mod file_error;
mod file_parts;
mod gltf_read;
mod gltf_write;
pub mod obj;
mod obj_doc;
mod ply_doc;
mod ply_row;
pub mod topology;
pub mod trimesh;
pub mod validate;

pub use document::{Corner, Face, FileMesh, MeshDocument, MeshFormat};
pub use file_error::MeshFileError;
pub use obj::{read_obj, write_obj};
pub use topology::Adjacency;
pub use trimesh::TriMesh;
pub use validate::{MeshError, MeshReport, validate_and_repair};
