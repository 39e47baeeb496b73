//! Axis-aligned bounding boxes of primitives, at one position or swept over a step.

use crate::Vec3;

/// An axis-aligned box `[min, max]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    /// The lower corner.
    pub min: Vec3,
    /// The upper corner.
    pub max: Vec3,
}

impl Aabb {
    /// The box of the points, grown by `margin` on every side.
    pub fn of_points<'a>(points: impl IntoIterator<Item = &'a Vec3>, margin: f64) -> Self {
        let mut b = Aabb {
            min: Vec3::repeat(f64::INFINITY),
            max: Vec3::repeat(f64::NEG_INFINITY),
        };
        for p in points {
            b.min = b.min.inf(p);
            b.max = b.max.sup(p);
        }
        b.min.add_scalar_mut(-margin);
        b.max.add_scalar_mut(margin);
        b
    }

    /// The box of the nodes `nodes` at positions `x`, and at `x1` too when given (the box
    /// swept by linear motion), grown by `margin`.
    pub fn of_nodes(nodes: &[usize], x: &[Vec3], x1: Option<&[Vec3]>, margin: f64) -> Self {
        let start = nodes.iter().map(|&n| &x[n]);
        match x1 {
            Some(x1) => Self::of_points(start.chain(nodes.iter().map(|&n| &x1[n])), margin),
            None => Self::of_points(start, margin),
        }
    }

    /// Whether the boxes share a point.
    pub fn overlaps(&self, other: &Aabb) -> bool {
        (0..3).all(|a| self.min[a] <= other.max[a] && other.min[a] <= self.max[a])
    }

    /// The longest side.
    pub fn longest_side(&self) -> f64 {
        (self.max - self.min).max()
    }
}
