//! The exact geometry kernel: points, lines, arcs, their intersections and distances, and
//! closed contours. Everything downstream is built from these types.

mod aabb;
mod arc;
mod cluster;
mod contour;
pub mod distance;
mod enclosing;
mod index;
pub mod intersect;
mod line;
mod packed;
mod pocket;
mod point;
mod prepared;
pub(crate) mod rounding;
mod segment;
mod stitch;
mod tolerance;
mod trig;

pub use aabb::Aabb;
pub use arc::{normalize_angle, Arc};
pub use cluster::{cluster_points, cluster_points_by};
pub use contour::{bbox_of, is_convex, signed_area, winding_number, Contour, WindingIndex};
pub use distance::{
    closest_param, closest_point, distance_from_segment, nearest_on, segment_distance, segments_nearer_than,
};
pub use enclosing::{enclosing_circle, farthest_from_segment, outline_points};
pub use index::{
    box_pairs, box_pairs_unsorted, for_each_overlapping_pair, overlapping_pairs, BoxIndex, SegmentIndex,
    Stopped,
};
pub use intersect::{intersect, Intersection, Intersections};
pub use line::Line;
pub use packed::{PackedTree, Search};
pub use pocket::Pocket;
pub use point::{Point, Vector};
pub use prepared::PreparedPocket;
pub use segment::Segment;
pub use stitch::{stitch, Piece, Source};
pub(crate) use stitch::{stitch_kept, PieceGraph};
pub use tolerance::{offset_slack, Tolerance, DEFAULT_JOIN_TOLERANCE, JOIN_SLACK, NEAR_REVERSAL, TOUCH};
pub use trig::sin_cos;
