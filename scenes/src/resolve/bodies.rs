//! The bodies of a scene as one mesh: each body's mesh built and placed, then joined into
//! one mesh of the scene's element, each body a [`Part`] of it; their groups joined too. The
//! cloth bodies' vertices come after the solids' (parts with no elements), their sheets
//! beside.

use super::cloth::cloth;
use super::mesh::{mesh_with_groups, SceneMesh};
use crate::error::SceneError;
use crate::format::{PlacementSpec, Scene, SCENE_BODY};
use isochor_mesh::element::{Part, TetElement};
use isochor_mesh::{ElementMesh, PhysicalGroup, PhysicalGroups, TetLocator, TetMesh, Vec3};
use isochor_solvers::ClothSheet;
use nalgebra::{Rotation3, Unit};

/// The bodies of a scene in the joined mesh.
#[derive(Debug, Clone)]
pub struct SceneBodies {
    /// Their names, in the scene's order ([`Scene::bodies`]).
    pub names: Vec<String>,
    /// Where each lies in the joined mesh.
    pub parts: Vec<Part>,
    /// The initial velocity of each, if given.
    pub velocities: Vec<Option<Vec3>>,
    /// The sheets of the cloth bodies, the last `cloths.len()` bodies.
    pub cloths: Vec<ClothSheet>,
}

impl SceneBodies {
    /// The one body of a scene without `[[bodies]]`, named `"body"`.
    pub fn one(mesh: &ElementMesh) -> Self {
        SceneBodies {
            names: vec![SCENE_BODY.to_string()],
            parts: vec![Part {
                vertices: 0..mesh.num_vertices(),
                mid_edge_nodes: mesh.num_vertices()..mesh.num_nodes(),
                elements: 0..mesh.num_elements(),
            }],
            velocities: vec![None],
            cloths: Vec::new(),
        }
    }

    /// The solid bodies' names and parts (every body but the cloths).
    pub fn solids(&self) -> impl Iterator<Item = (&str, &Part)> {
        let solids = self.names.len() - self.cloths.len();
        self.names
            .iter()
            .map(String::as_str)
            .zip(&self.parts)
            .take(solids)
    }

    /// The index of the body `name`, or the message naming the bodies there are.
    pub fn index(&self, name: &str) -> Result<usize, String> {
        self.names
            .iter()
            .position(|n| n == name)
            .ok_or_else(|| format!("no body named '{name}' (bodies: {})", self.names.join(", ")))
    }

    /// The body of each element, for the frames' `body` field.
    pub fn element_bodies(&self) -> Vec<i32> {
        let mut ids = Vec::new();
        for (b, part) in self.parts.iter().enumerate() {
            ids.extend(part.elements.clone().map(|_| b as i32));
        }
        ids
    }

    /// The body of every node of a mesh of `num_nodes` nodes.
    pub fn node_bodies(&self, num_nodes: usize) -> Vec<usize> {
        let mut bodies = vec![0; num_nodes];
        for (b, part) in self.parts.iter().enumerate() {
            part.nodes().for_each(|n| bodies[n] = b);
        }
        bodies
    }

    /// The initial velocity of every node, or `None` if no body has one.
    pub fn initial_velocities(&self, num_nodes: usize) -> Option<Vec<Vec3>> {
        if self.velocities.iter().all(Option::is_none) {
            return None;
        }
        let mut v = vec![Vec3::zeros(); num_nodes];
        for (part, velocity) in self.parts.iter().zip(&self.velocities) {
            if let Some(velocity) = velocity {
                part.nodes().for_each(|n| v[n] = *velocity);
            }
        }
        Some(v)
    }
}

/// Builds every solid body's mesh (with its groups when `groups` is set), places it, and
/// joins them; a scene of one unplaced body keeps its mesh exactly. Refuses bodies that
/// overlap at the start, naming both and how many surface nodes of one lie inside the other.
/// Then appends each cloth body's vertices ([`cloth`]; they stay out of the overlap check).
pub fn build_bodies(
    scene: &Scene,
    element: TetElement,
    groups: bool,
) -> Result<(SceneMesh, SceneBodies), SceneError> {
    let (mut mesh, mut bodies) = build_solids(scene, element, groups)?;
    let cloths = scene.cloths();
    if cloths.is_empty() {
        return Ok((mesh, bodies));
    }
    if mesh.mesh.kind() != TetElement::Tet4 {
        return Err(invalid(
            scene,
            "element".into(),
            "a cloth sits beside 4-node tets only".into(),
        ));
    }
    let corners = mesh.mesh.corners();
    let mut positions = corners.positions().to_vec();
    let elements = corners.num_tets();
    for body in &cloths {
        let first = positions.len();
        let cloth = cloth(scene, body, first)?;
        positions.extend(&cloth.vertices);
        bodies.names.push(body.name.to_string());
        bodies.parts.push(Part {
            vertices: first..positions.len(),
            mid_edge_nodes: positions.len()..positions.len(),
            elements: elements..elements,
        });
        bodies.velocities.push(body.velocity.map(Vec3::from));
        bodies.cloths.push(cloth.sheet);
    }
    let joined = TetMesh::new(positions, corners.tets().to_vec())?;
    mesh.mesh = ElementMesh::linear(joined);
    let solids = bodies.names.len() - bodies.cloths.len();
    refuse_overlaps(scene, &mesh.mesh, &bodies, solids)?;
    Ok((mesh, bodies))
}

/// The solid bodies of [`build_bodies`], joined.
fn build_solids(
    scene: &Scene,
    element: TetElement,
    groups: bool,
) -> Result<(SceneMesh, SceneBodies), SceneError> {
    let bodies = scene.bodies();
    let mut meshes = Vec::with_capacity(bodies.len());
    for body in &bodies {
        let mut built = mesh_with_groups(body.mesh, element, groups)?;
        if let Some(place) = body.place {
            built.mesh = built
                .mesh
                .mapped(placement(place))
                .map_err(|e| invalid(scene, body.key("place"), e.to_string()))?;
        }
        meshes.push(built);
    }
    let names = bodies.iter().map(|b| b.name.to_string()).collect();
    let velocities = bodies.iter().map(|b| b.velocity.map(Vec3::from)).collect();
    if let [_] = meshes[..] {
        let only = meshes.remove(0);
        let parts = SceneBodies::one(&only.mesh).parts;
        return Ok((
            only,
            SceneBodies {
                names,
                parts,
                velocities,
                cloths: Vec::new(),
            },
        ));
    }
    let sources: Vec<String> = meshes.iter().map(|m| m.source.clone()).collect();
    let mut groups = Vec::new();
    let mut element_meshes = Vec::new();
    let mut notices = Vec::new();
    for m in meshes {
        groups.push(m.groups);
        element_meshes.push(m.mesh);
        notices.extend(m.notices);
    }
    let (mesh, parts) = ElementMesh::disjoint_union(element_meshes)?;
    let bodies = SceneBodies {
        names,
        parts,
        velocities,
        cloths: Vec::new(),
    };
    refuse_overlaps(scene, &mesh, &bodies, 0)?;
    Ok((
        SceneMesh {
            groups: joined_groups(&groups, &bodies.parts),
            mesh,
            source: format!("the bodies' meshes ({})", sources.join("; ")),
            notices,
        },
        bodies,
    ))
}

fn invalid(scene: &Scene, key: String, message: String) -> SceneError {
    SceneError::Invalid {
        origin: format!("scene {}", scene.name),
        key,
        message,
    }
}

/// The rigid map of a placement: the rotation about its axis, then the translation.
pub(super) fn placement(place: &PlacementSpec) -> impl Fn(&Vec3) -> Vec3 {
    let rotation = place.rotate.as_ref().map(|r| {
        let axis = Unit::new_normalize(Vec3::from(r.axis));
        (
            Vec3::from(r.center),
            Rotation3::from_axis_angle(&axis, r.degrees.to_radians()),
        )
    });
    let offset = place.translate.map_or(Vec3::zeros(), Vec3::from);
    move |x| {
        let turned = match &rotation {
            Some((center, r)) => center + r * (x - center),
            None => *x,
        };
        turned + offset
    }
}

/// The groups of every body in the joined mesh's numbering; groups of one key and dimension
/// in several bodies become one (a selection's `body` restricts it to one body).
fn joined_groups(groups: &[Option<PhysicalGroups>], parts: &[Part]) -> Option<PhysicalGroups> {
    if groups.iter().all(Option::is_none) {
        return None;
    }
    let mut joined: Vec<PhysicalGroup> = Vec::new();
    for (body_groups, part) in groups.iter().zip(parts) {
        let Some(body_groups) = body_groups else {
            continue;
        };
        let (v0, e0) = (part.vertices.start, part.elements.start);
        for (_, g) in body_groups.iter() {
            let faces = g.faces.iter().map(|f| f.map(|v| v + v0));
            let tets = g.tets.iter().map(|e| e + e0);
            match joined
                .iter_mut()
                .find(|j| j.dimension == g.dimension && j.name == g.name && j.tag == g.tag)
            {
                Some(j) => {
                    j.faces.extend(faces);
                    j.tets.extend(tets);
                }
                None => joined.push(PhysicalGroup {
                    faces: faces.collect(),
                    tets: tets.collect(),
                    ..g.clone()
                }),
            }
        }
    }
    Some(PhysicalGroups::new(joined))
}

/// Refuses two bodies of which one has boundary vertices (a cloth: any vertex) strictly
/// inside the other (a solid), for the bodies from `from` on against every solid.
fn refuse_overlaps(
    scene: &Scene,
    mesh: &ElementMesh,
    bodies: &SceneBodies,
    from: usize,
) -> Result<(), SceneError> {
    let corners = mesh.corners();
    let surface = corners.boundary()?;
    let mut on_surface = vec![false; corners.num_vertices()];
    surface
        .triangles()
        .iter()
        .flatten()
        .for_each(|&v| on_surface[v] = true);
    let x = corners.positions();
    let body_box = |part: &Part| {
        part.vertices.clone().fold(
            (x[part.vertices.start], x[part.vertices.start]),
            |(lo, hi), v| (lo.inf(&x[v]), hi.sup(&x[v])),
        )
    };
    let solids = bodies.parts.iter().enumerate();
    for (a, part_a) in solids.filter(|(_, p)| !p.elements.is_empty()) {
        let (lo, hi) = body_box(part_a);
        // The body alone as a mesh, for point location.
        let tets: Vec<[usize; 4]> = part_a
            .elements
            .clone()
            .map(|e| corners.tets()[e].map(|v| v - part_a.vertices.start))
            .collect();
        let alone = isochor_mesh::TetMesh::new(x[part_a.vertices.clone()].to_vec(), tets)?;
        let locator = TetLocator::new(&alone)?;
        let others = bodies.parts.iter().enumerate().skip(from);
        for (b, part_b) in others.filter(|&(b, _)| b != a) {
            let cloth = part_b.elements.is_empty();
            let inside = part_b
                .vertices
                .clone()
                .filter(|&v| on_surface[v] || cloth)
                .filter(|&v| {
                    let p = &x[v];
                    (0..3).all(|k| p[k] >= lo[k] && p[k] <= hi[k]) && locator.contains(p)
                })
                .count();
            if inside > 0 {
                return Err(invalid(
                    scene,
                    "bodies".into(),
                    format!(
                        "bodies '{}' and '{}' overlap at the start: {inside} {}nodes of '{}' lie inside '{}'; place them apart (`place`)",
                        bodies.names[a], bodies.names[b], if cloth { "" } else { "surface " }, bodies.names[b], bodies.names[a]
                    ),
                ));
            }
        }
    }
    Ok(())
}
