//! Triangle meshes: the mesh type, OBJ input and output, topology and validation.

pub mod obj;
pub mod obj_doc;
pub mod topology;
pub mod trimesh;
pub mod validate;

pub use obj::{ObjError, read_obj, write_obj};
pub use obj_doc::{Corner, ObjDocument, ObjFace};
pub use topology::Adjacency;
pub use trimesh::TriMesh;
pub use validate::{MeshError, MeshReport, validate_and_repair};
