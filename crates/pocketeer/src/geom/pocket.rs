//! A pocket: the region every stage works on, from nesting to the check.

use super::Contour;

/// A pocket: the area inside a counter-clockwise boundary and outside its clockwise islands.
///
/// ```
/// use pocketeer::geom::{Arc, Contour, Point, Pocket};
/// let p = Point::new;
/// let boundary = Contour::polygon(&[p(0.0, 0.0), p(40.0, 0.0), p(40.0, 30.0), p(0.0, 30.0)]);
/// let island = Contour::new(vec![pocketeer::geom::Segment::Arc(Arc::new(p(20.0, 15.0), 5.0, 0.0, -std::f64::consts::TAU))]);
/// let pocket = Pocket { boundary, islands: vec![island] };
/// assert!((pocket.area() - (1200.0 - std::f64::consts::PI * 25.0)).abs() < 1e-9);
/// assert_eq!(pocket.contours().count(), 2);
/// ```
#[derive(Debug, Clone)]
pub struct Pocket {
    /// Outer boundary, counter-clockwise.
    pub boundary: Contour,
    /// Islands, clockwise.
    pub islands: Vec<Contour>,
}

impl Pocket {
    /// The boundary, then the islands.
    pub fn contours(&self) -> impl Iterator<Item = &Contour> {
        std::iter::once(&self.boundary).chain(&self.islands)
    }

    /// Area of material to remove: boundary area minus island areas.
    pub fn area(&self) -> f64 {
        self.boundary.signed_area() + self.islands.iter().map(Contour::signed_area).sum::<f64>()
    }
}
