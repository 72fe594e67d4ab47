//! The body: its mesh ([`mesh`](self::mesh)), loading and analysis ([`load`]), landmarks,
//! section rings, partitions A-G, and the body index with its near-point tree.

pub mod index;
pub mod index_cache;
pub mod landmarks;
pub mod load;
pub mod mesh;
pub mod near_tree;
pub mod nearby;
pub mod orient;
pub mod partition;
pub mod profile;
pub mod rings;
pub mod shell;
pub mod slices;

pub use landmarks::{
    ArmAxis, Landmark, LandmarkError, LandmarkKind, LandmarkOptions, LandmarkOverride, Landmarks, Side, girth_across,
};
pub use load::{Body, BodyError, build_partitions, cut_rings, find_landmarks};
pub use mesh::{BUILTIN_BODY_NAME, BUILTIN_BODY_OBJ, BodyMesh, BodySource};
pub use orient::{Axis, Frame, PoseError, check_pose};
pub use partition::{DetectionMethod, Partition, PartitionId, PartitionOptions, ResponseRule};
pub use rings::{BodyRing, RingError};
