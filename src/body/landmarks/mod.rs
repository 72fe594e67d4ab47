//! Automatic body landmarks from the horizontal section profile.
//!
//! Everything is found from events and extremes of the sections, never from fixed
//! heights, so any standing body with legs and arms apart works:
//!
//! * **crotch**: scanning up from the feet, the two leg loops are tracked (each level's
//!   leg is the loop holding the previous level's leg centroid); the crotch is the height
//!   where one loop first holds both, refined by bisection.
//! * **ankle**: the smallest leg tape girth above the foot's largest; **knee**: the smallest leg girth above
//!   the calf (the first local girth maximum above the ankle).
//! * **armpit**: scanning up the torso, loops beside it of at least 2% of its area are arms;
//!   the armpit is where the last of them joins the torso loop, refined by bisection.
//! * **waist**: the smallest torso tape girth in the middle half between crotch and armpit;
//!   **hip**: the greatest buttock protrusion (rearmost torso point) below the waist;
//!   **bust**: the largest tape girth above the waist.
//! * **neck** (narrowest): the first girth minimum above the armpit that is followed by a
//!   rise of 10% (the head).
//! * **shoulder** and **side neck**: on the front silhouette (half width against height
//!   from armpit to neck), the shoulder point is the convex corner farthest outside the
//!   chord, the side neck point the concave corner farthest inside the chord from the
//!   shoulder to the neck. **front neck**: the same concave corner on the mid-sagittal
//!   front profile between bust and neck.
//!
//! Left is `+x` (the body faces `+z`, `y` up).

mod arms;
mod detect;
mod legs;
mod neck;
mod overrides;
mod scan;
mod torso;
mod types;

pub use arms::{bend, girth_across};
pub use detect::detect_landmarks;
pub use types::{ArmAxis, Landmark, LandmarkError, LandmarkKind, LandmarkOptions, LandmarkOverride, Landmarks, Side};
