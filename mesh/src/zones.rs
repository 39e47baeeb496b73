//! Volume zones: possibly overlapping sets of tets (Sheen et al. 2021, sec. 4 and 6).

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
}
