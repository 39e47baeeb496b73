//! Volume zones: possibly overlapping sets of tets (Sheen et al. 2021, sec. 4 and 6).
//!
//! Each zone carries one volume constraint (eq. 6 of Sheen et al. 2021). Zones come from the
//! whole mesh ([`Zones::global`], the "hydrostatic" case of Fig. 5a), from k-rings around
//! seed vertices ([`Zones::k_ring_cover`], Fig. 5b-d) or from labels painted on the surface
//! ([`Zones::painted`], sec. 6 and Fig. 4).

use crate::adjacency::RingScratch;
use crate::closest::TriangleBvh;
use crate::{Adjacency, BoundarySurface, MeshError, TetMesh};
use rayon::prelude::*;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// A list of zones; each zone is a sorted, duplicate-free list of tet indices.
/// Zones may overlap (a tet may belong to several zones).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Zones {
    zones: Vec<Vec<usize>>,
}

impl Zones {
    /// Zones from explicit tet lists (sorted and de-duplicated here).
    pub fn from_sets(mut zones: Vec<Vec<usize>>) -> Self {
        for z in &mut zones {
            z.sort_unstable();
            z.dedup();
        }
        Zones { zones }
    }

    /// One zone holding every tet: the whole body keeps its volume (a "water balloon",
    /// Sheen et al. 2021, Fig. 5a).
    pub fn global(mesh: &TetMesh) -> Self {
        Zones {
            zones: vec![(0..mesh.num_tets()).collect()],
        }
    }

    /// A cover of the mesh by overlapping k-ring zones (Sheen et al. 2021, Fig. 5b-d; the
    /// k-ring is defined in [`Adjacency::k_ring`]).
    ///
    /// Seeding rule (greedy set cover): repeatedly take the vertex whose k-ring contains the
    /// most tets not yet in any zone (ties to the lowest vertex index) and add its whole
    /// k-ring as a zone, until every tet is covered. Zones overlap where rings meet; the
    /// number of zones is within a factor `ln(tets per ring)` of the smallest possible cover.
    pub fn k_ring_cover(mesh: &TetMesh, k: usize) -> Result<Self, MeshError> {
        if k == 0 {
            return Err(MeshError::parameter("k", k, "a k-ring needs k >= 1"));
        }
        let adjacency = Adjacency::new(mesh);
        let mut scratch = RingScratch::new(&adjacency);
        let mut ring = Vec::new();
        let mut covered = vec![false; mesh.num_tets()];
        let mut remaining = mesh.num_tets();
        // Lazy greedy: heap keys are upper bounds of each vertex's gain (gains only shrink);
        // a vertex is taken once its exact gain beats every other bound.
        let mut heap: BinaryHeap<(usize, Reverse<usize>)> = (0..mesh.num_vertices())
            .map(|v| (usize::MAX, Reverse(v)))
            .collect();
        let mut zones = Vec::new();
        while remaining > 0 {
            let Some((_, Reverse(v))) = heap.pop() else {
                break;
            };
            adjacency.k_ring_into(v, k, &mut scratch, &mut ring);
            let gain = ring.iter().filter(|&&e| !covered[e]).count();
            if gain == 0 {
                continue;
            }
            if heap.peek().is_some_and(|&top| top > (gain, Reverse(v))) {
                heap.push((gain, Reverse(v)));
                continue;
            }
            for &e in &ring {
                if !covered[e] {
                    covered[e] = true;
                    remaining -= 1;
                }
            }
            zones.push(ring.clone());
        }
        Ok(Zones::from_sets(zones))
    }

    /// Zones painted on the surface (Sheen et al. 2021, sec. 6).
    ///
    /// `labels[v]` lists the zones of vertex `v` (several labels make zones overlap); only
    /// surface vertices are read, so `labels` has one entry per mesh vertex and interior
    /// entries are ignored. A surface triangle takes the labels shared by all three of its
    /// vertices, or, if they share none, the union of their labels. Each tet then copies the
    /// labels of the surface triangle closest to its centroid (exact point-triangle distance,
    /// standing in for the paper's projection along a distance-field gradient). Zone `z`
    /// holds the tets labelled `z`; the number of zones is the largest label plus one, and
    /// every zone must receive at least one tet.
    pub fn painted(mesh: &TetMesh, labels: &[Vec<usize>]) -> Result<Self, MeshError> {
        if labels.len() != mesh.num_vertices() {
            return Err(MeshError::parameter(
                "labels",
                format!("{} entries", labels.len()),
                format!("need one entry per mesh vertex ({})", mesh.num_vertices()),
            ));
        }
        let surface = BoundarySurface::new(mesh)?;
        let count = surface
            .vertices()
            .iter()
            .flat_map(|&v| labels[v].iter().map(|&z| z.saturating_add(1)))
            .max()
            .ok_or_else(|| {
                MeshError::parameter("labels", "none", "no surface vertex has a label")
            })?;
        if count > mesh.num_tets() {
            return Err(MeshError::parameter(
                "labels",
                count - 1,
                format!("more zones than tets ({})", mesh.num_tets()),
            ));
        }
        let triangle_labels: Vec<Vec<usize>> = surface
            .triangles()
            .iter()
            .map(|t| triangle_labels(t.map(|v| labels[v].as_slice())))
            .collect();
        let bvh = TriangleBvh::new(surface.triangles(), mesh.positions());
        let nearest: Vec<usize> = (0..mesh.num_tets())
            .into_par_iter()
            .map(|e| bvh.closest(&mesh.centroid(e)).map_or(0, |(t, _)| t))
            .collect();
        let mut zones = vec![Vec::new(); count];
        for (e, &t) in nearest.iter().enumerate() {
            for &z in &triangle_labels[t] {
                zones[z].push(e);
            }
        }
        if let Some(zone) = zones.iter().position(Vec::is_empty) {
            return Err(MeshError::EmptyZone { zone });
        }
        Ok(Zones { zones })
    }

    /// Number of zones.
    pub fn len(&self) -> usize {
        self.zones.len()
    }

    /// Whether there are no zones.
    pub fn is_empty(&self) -> bool {
        self.zones.is_empty()
    }

    /// The tets of zone `z`.
    pub fn zone(&self, z: usize) -> &[usize] {
        &self.zones[z]
    }

    /// All zones.
    pub fn iter(&self) -> impl Iterator<Item = &[usize]> {
        self.zones.iter().map(Vec::as_slice)
    }

    /// For output: the first zone of every tet, or -1 for a tet in no zone. Fails if a zone
    /// names a tet `>= num_tets`.
    pub fn tet_zone_ids(&self, num_tets: usize) -> Result<Vec<i32>, MeshError> {
        let mut ids = vec![-1; num_tets];
        for (z, zone) in self.zones.iter().enumerate().rev() {
            let id = i32::try_from(z)
                .map_err(|_| MeshError::parameter("zones", z, "zone id exceeds i32"))?;
            for &e in zone {
                *ids.get_mut(e).ok_or(MeshError::TetOutOfRange {
                    tet: e,
                    tets: num_tets,
                })? = id;
            }
        }
        Ok(ids)
    }
}

/// Labels shared by all three vertices, or else the union of their labels (sorted).
fn triangle_labels(vertex_labels: [&[usize]; 3]) -> Vec<usize> {
    let [a, b, c] = vertex_labels;
    let mut shared: Vec<usize> = a
        .iter()
        .copied()
        .filter(|z| b.contains(z) && c.contains(z))
        .collect();
    if shared.is_empty() {
        shared = a.iter().chain(b).chain(c).copied().collect();
    }
    shared.sort_unstable();
    shared.dedup();
    shared
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::box_grid;
    use crate::Vec3;

    #[test]
    fn global_zone_holds_every_tet() {
        let mesh = box_grid(Vec3::zeros(), Vec3::repeat(1.0), [2, 2, 2]).unwrap();
        let z = Zones::global(&mesh);
        assert_eq!(z.len(), 1);
        assert_eq!(z.zone(0).len(), mesh.num_tets());
        assert_eq!(
            z.tet_zone_ids(mesh.num_tets()).unwrap(),
            vec![0; mesh.num_tets()]
        );
    }

    #[test]
    fn k_ring_cover_covers_with_overlapping_rings() {
        // The beam of Sheen et al. 2021, Fig. 5: 16 x 4 x 4 vertices.
        let mesh = box_grid(Vec3::zeros(), Vec3::new(15.0, 3.0, 3.0), [15, 3, 3]).unwrap();
        let adjacency = Adjacency::new(&mesh);
        let mut previous = usize::MAX;
        for k in 1..=4 {
            let zones = Zones::k_ring_cover(&mesh, k).unwrap();
            let mut hits = vec![0; mesh.num_tets()];
            for zone in zones.iter() {
                for &e in zone {
                    hits[e] += 1;
                }
                // Every zone is exactly the k-ring of some vertex.
                let is_ring =
                    (0..mesh.num_vertices()).any(|v| adjacency.k_ring(v, k).unwrap() == zone);
                assert!(is_ring, "k = {k}: a zone is not a k-ring");
            }
            assert!(hits.iter().all(|&h| h >= 1), "k = {k}: a tet is uncovered");
            assert!(
                hits.iter().any(|&h| h >= 2),
                "k = {k}: rings should overlap"
            );
            assert!(
                zones.len() < previous,
                "k = {k}: larger rings need fewer zones"
            );
            // The cover is far smaller than one ring per vertex.
            assert!(zones.len() * 3 < mesh.num_vertices());
            previous = zones.len();
        }
        assert!(Zones::k_ring_cover(&mesh, 0).is_err());
    }

    #[test]
    fn painted_halves_come_back_as_halves() {
        let mesh = box_grid(Vec3::zeros(), Vec3::repeat(1.0), [6, 4, 5]).unwrap();
        let labels: Vec<Vec<usize>> = mesh
            .positions()
            .iter()
            .map(|p| match p.x {
                x if x < 0.5 => vec![0],
                x if x > 0.5 => vec![1],
                _ => vec![0, 1],
            })
            .collect();
        let zones = Zones::painted(&mesh, &labels).unwrap();
        assert_eq!(zones.len(), 2);
        let left: Vec<usize> = (0..mesh.num_tets())
            .filter(|&e| mesh.centroid(e).x < 0.5)
            .collect();
        let right: Vec<usize> = (0..mesh.num_tets())
            .filter(|&e| mesh.centroid(e).x > 0.5)
            .collect();
        assert_eq!(zones.zone(0), left.as_slice());
        assert_eq!(zones.zone(1), right.as_slice());
        let ids = zones.tet_zone_ids(mesh.num_tets()).unwrap();
        assert!(left.iter().all(|&e| ids[e] == 0) && right.iter().all(|&e| ids[e] == 1));
    }

    #[test]
    fn painted_overlaps_and_errors() {
        let mesh = box_grid(Vec3::zeros(), Vec3::repeat(1.0), [4, 4, 4]).unwrap();
        // Everything in zone 0, the top half also in zone 1.
        let labels: Vec<Vec<usize>> = mesh
            .positions()
            .iter()
            .map(|p| if p.z > 0.5 { vec![0, 1] } else { vec![0] })
            .collect();
        let zones = Zones::painted(&mesh, &labels).unwrap();
        assert_eq!(zones.zone(0).len(), mesh.num_tets());
        assert!(!zones.zone(1).is_empty() && zones.zone(1).len() < mesh.num_tets());
        assert!(zones.zone(1).iter().all(|&e| mesh.centroid(e).z > 0.5));
        // Label 2 is never used by any vertex: zone 1 is empty.
        let skipped: Vec<Vec<usize>> = labels
            .iter()
            .map(|l| l.iter().map(|z| 2 * z).collect())
            .collect();
        let e = Zones::painted(&mesh, &skipped).unwrap_err();
        assert!(matches!(e, MeshError::EmptyZone { zone: 1 }));
        assert!(Zones::painted(&mesh, &labels[1..]).is_err());
        assert!(Zones::painted(&mesh, &vec![Vec::new(); mesh.num_vertices()]).is_err());
        let bad = Zones::from_sets(vec![vec![0, 10_000]]);
        assert!(matches!(
            bad.tet_zone_ids(mesh.num_tets()),
            Err(MeshError::TetOutOfRange { tet: 10_000, .. })
        ));
    }
}
