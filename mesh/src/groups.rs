//! Named groups of boundary faces or tets of a mesh: the physical groups of a Gmsh file
//! (surfaces and volumes), the regions of a TetGen file, and the groups a generator names
//! (a chamber's walls, a clamped base), so that scenes select them by name alike.

use std::collections::{BTreeMap, HashMap};

/// One physical group of surfaces (dimension 2) or volumes (dimension 3).
#[derive(Debug, Clone, PartialEq)]
pub struct PhysicalGroup {
    /// 2 for a surface group, 3 for a volume group.
    pub dimension: usize,
    /// The group's number (in a Gmsh file, its physical tag).
    pub tag: i64,
    /// Its name (in a Gmsh file, from `$PhysicalNames`), if any.
    pub name: Option<String>,
    /// Its triangles, as corner vertex indices of the mesh (as listed in a file).
    pub faces: Vec<[usize; 3]>,
    /// Its tets, as element indices of the mesh.
    pub tets: Vec<usize>,
}

/// Physical groups by key: a group's name, or for an unnamed group its tag (`"7"`); when two
/// groups would share a key (a surface and a volume group of the same name or tag), both keys
/// are prefixed with the dimension (`"2:7"`, `"3:7"`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PhysicalGroups {
    groups: BTreeMap<String, PhysicalGroup>,
}

impl PhysicalGroups {
    /// The groups `groups`, keyed as above.
    pub fn new(groups: Vec<PhysicalGroup>) -> Self {
        let key = |g: &PhysicalGroup| g.name.clone().unwrap_or_else(|| g.tag.to_string());
        let mut uses = HashMap::new();
        for g in &groups {
            *uses.entry(key(g)).or_insert(0) += 1;
        }
        let groups = groups
            .into_iter()
            .map(|g| {
                let k = key(&g);
                let k = if uses[&k] > 1 {
                    format!("{}:{k}", g.dimension)
                } else {
                    k
                };
                (k, g)
            })
            .collect();
        PhysicalGroups { groups }
    }

    /// The group of `key`.
    pub fn get(&self, key: &str) -> Option<&PhysicalGroup> {
        self.groups.get(key)
    }

    /// The keys of all groups, sorted.
    pub fn keys(&self) -> impl Iterator<Item = &str> {
        self.groups.keys().map(String::as_str)
    }

    /// The groups with their keys, sorted by key.
    pub fn iter(&self) -> impl Iterator<Item = (&str, &PhysicalGroup)> {
        self.groups.iter().map(|(k, g)| (k.as_str(), g))
    }

    /// Number of groups.
    pub fn len(&self) -> usize {
        self.groups.len()
    }

    /// Whether there is no group.
    pub fn is_empty(&self) -> bool {
        self.groups.is_empty()
    }
}

/// The vertex index [`ElementMesh::from_nodes`](crate::ElementMesh::from_nodes) gives each of
/// `num_nodes` input nodes that is a corner of an element of `connectivity` (`nodes_per_element`
/// indices each): the corners are numbered first, in input order. A group's triangles, listed
/// by input nodes, are renumbered by it.
pub fn corner_numbering(
    connectivity: &[usize],
    nodes_per_element: usize,
    num_nodes: usize,
) -> Vec<Option<usize>> {
    let mut vertex = vec![None; num_nodes];
    for element in connectivity.chunks_exact(nodes_per_element) {
        for &i in &element[..4] {
            if let Some(v) = vertex.get_mut(i) {
                *v = Some(0);
            }
        }
    }
    for (count, v) in vertex.iter_mut().flatten().enumerate() {
        *v = count;
    }
    vertex
}

impl PhysicalGroup {
    /// A named surface group of `faces` (corner triangles) with number `tag`.
    pub fn surface(name: &str, tag: i64, faces: Vec<[usize; 3]>) -> Self {
        PhysicalGroup {
            dimension: 2,
            tag,
            name: Some(name.to_string()),
            faces,
            tets: Vec::new(),
        }
    }
}
