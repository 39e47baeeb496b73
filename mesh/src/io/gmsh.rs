//! Gmsh `.msh` reader, ASCII formats 2.2 and 4.1: 4-node tetrahedra (element type 4) or
//! 10-node tetrahedra (type 11, Gmsh's node order, which is ours) are read; points, lines,
//! triangles (3- and 6-node, types 2 and 9) and quads are skipped, since the boundary faces
//! follow from the tets ([`crate::ElementMesh::boundary`]); other volume elements, and files
//! mixing 4- and 10-node tets, are rejected.
//!
//! [`read_gmsh_with_groups`] also reads the physical groups of surfaces and volumes: their
//! names (`$PhysicalNames`), their triangles (3- and 6-node, by their corners) and tets, and
//! the names of point and curve groups (without elements). An element's groups are the first
//! tag of its lines in format 2.2 (which writes an element of several groups once per group:
//! the lines are read as one element), and the physical tags of its entity (`$Entities`) in
//! format 4.1.

use super::text::{excerpt, Fields, Lines};
use super::{assemble, read_text, Cells, FileNodes};
use crate::element::TetElement;
use crate::{corner_numbering, PhysicalGroup, PhysicalGroups};
use crate::{ElementMesh, MeshError, TetMesh, Vec3};
use std::collections::{BTreeMap, HashMap};
use std::path::Path;

/// Reads a Gmsh ASCII mesh (format 2.x or 4.1) of 4-node tets. Vertices that no tetrahedron
/// uses are dropped; negatively oriented tets are re-oriented (see [`TetMesh::reoriented`]).
/// A file of 10-node tets is refused at its first tet's line: read it with
/// [`read_gmsh_elements`].
pub fn read_gmsh(path: impl AsRef<Path>) -> Result<TetMesh, MeshError> {
    let path = path.as_ref();
    let (nodes, cells, _) = parse(path, &read_text(path)?)?;
    linear(path, nodes, cells)
}

/// The linear mesh of parsed nodes and 4-node tets; 10-node tets are refused.
fn linear(path: &Path, nodes: FileNodes, cells: Cells) -> Result<TetMesh, MeshError> {
    if cells.kind == TetElement::Tet10 {
        return Err(MeshError::parse(
            path,
            cells.lines[0],
            "the file holds 10-node (quadratic) tetrahedra: read it with read_gmsh_elements \
             (its corner mesh is the ElementMesh's corners())",
        ));
    }
    Ok(assemble(path, nodes, cells)?.into_corners())
}

/// Reads a Gmsh ASCII mesh (format 2.x or 4.1) of 4- or 10-node tets into an
/// [`ElementMesh`] of the file's order (see [`ElementMesh::from_nodes`]: nodes are
/// renumbered corners first, unused nodes dropped, negative tets re-oriented with their
/// mid-edge nodes). A bad element is reported at its line.
pub fn read_gmsh_elements(path: impl AsRef<Path>) -> Result<ElementMesh, MeshError> {
    let path = path.as_ref();
    let (nodes, cells, _) = parse(path, &read_text(path)?)?;
    assemble(path, nodes, cells)
}

/// Reads a Gmsh mesh like [`read_gmsh_elements`] with its physical groups of dimension 2
/// (surfaces) and 3 (volumes), their vertices numbered as the mesh's, and the named point
/// and curve groups (dimension 0 and 1, without elements). Fails at its line on a
/// triangle with a node that is no tet's corner.
///
/// ```
/// use isochor_mesh::io::read_gmsh_with_groups;
///
/// // One tet with its base triangle in the surface group "base" (Gmsh format 2.2).
/// let msh = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n\
///            $PhysicalNames\n2\n2 1 \"base\"\n3 2 \"body\"\n$EndPhysicalNames\n\
///            $Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n\
///            $Elements\n2\n1 2 2 1 1 1 3 2\n2 4 2 2 1 1 2 3 4\n$EndElements\n";
/// let path = std::env::temp_dir().join(format!("isochor-doc-{}.msh", std::process::id()));
/// std::fs::write(&path, msh).unwrap();
/// let (mesh, groups) = read_gmsh_with_groups(&path)?;
/// std::fs::remove_file(&path).unwrap();
/// assert_eq!(mesh.num_elements(), 1);
/// assert_eq!(groups.keys().collect::<Vec<_>>(), ["base", "body"]);
/// assert_eq!(groups.get("base").unwrap().faces, [[0, 2, 1]]);
/// assert_eq!(groups.get("body").unwrap().tets, [0]);
/// # Ok::<(), isochor_mesh::MeshError>(())
/// ```
pub fn read_gmsh_with_groups(
    path: impl AsRef<Path>,
) -> Result<(ElementMesh, PhysicalGroups), MeshError> {
    let path = path.as_ref();
    let (nodes, cells, raw) = parse(path, &read_text(path)?)?;
    let vertex = corner_numbering(
        &cells.connectivity,
        cells.kind.num_nodes(),
        nodes.positions.len(),
    );
    let mut groups = Vec::new();
    for ((dimension, tag), group) in raw.groups {
        let name = raw.names.get(&(dimension, tag)).cloned();
        let faces = group
            .faces
            .iter()
            .map(|(face, line)| {
                face.iter()
                    .map(|&i| {
                        vertex[i].ok_or_else(|| {
                            MeshError::parse(
                                path,
                                *line,
                                format!(
                                    "triangle node {} of physical group {tag} is not a corner of any tetrahedron",
                                    nodes.tags[i]
                                ),
                            )
                        })
                    })
                    .collect::<Result<Vec<_>, _>>()
                    .map(|v| [v[0], v[1], v[2]])
            })
            .collect::<Result<_, _>>()?;
        groups.push(PhysicalGroup {
            dimension,
            tag,
            name,
            faces,
            tets: group.tets,
        });
    }
    let mesh = assemble(path, nodes, cells)?;
    Ok((mesh, PhysicalGroups::new(groups)))
}

/// The node positions (in file order) and every triangle's corners (indices into them) of a
/// Gmsh file, tets or none: the surface of a rigid obstacle
/// ([`super::read_gmsh_surface`]).
pub(super) fn read_triangles(path: &Path) -> Result<(Vec<Vec3>, Vec<[usize; 3]>), MeshError> {
    let (nodes, _, raw) = parse(path, &read_text(path)?)?;
    Ok((nodes.positions, raw.triangles))
}

/// The elements of one physical group as read: triangles (file node indices, line) and tets.
#[derive(Default)]
struct RawGroup {
    faces: Vec<([usize; 3], usize)>,
    tets: Vec<usize>,
}

/// Physical groups as read: names and elements by `(dimension, tag)`, and (format 4.1) the
/// physical tags of each `(dimension, entity tag)`.
#[derive(Default)]
struct RawGroups {
    names: HashMap<(usize, i64), String>,
    groups: BTreeMap<(usize, i64), RawGroup>,
    entities: HashMap<(usize, i64), Vec<i64>>,
    /// Every triangle read (file node indices of its corners), in a group or not.
    triangles: Vec<[usize; 3]>,
}

impl RawGroups {
    /// Records a triangle (file node indices of its corners) read at `line`, and in the
    /// groups `tags` (0 = none).
    fn add_face(&mut self, tags: &[i64], face: [usize; 3], line: usize) {
        self.triangles.push(face);
        for &tag in tags.iter().filter(|&&t| t != 0) {
            let group = self.groups.entry((2, tag)).or_default();
            group.faces.push((face, line));
        }
    }

    /// Records tet `tet` in the groups `tags` (0 = none).
    fn add_tet(&mut self, tags: &[i64], tet: usize) {
        for &tag in tags.iter().filter(|&&t| t != 0) {
            self.groups.entry((3, tag)).or_default().tets.push(tet);
        }
    }
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Version {
    V2,
    V41,
}

/// Nodes by tag: positions, tags and tag -> index.
#[derive(Default)]
struct Nodes {
    positions: Vec<Vec3>,
    tags: Vec<usize>,
    index: HashMap<usize, usize>,
}

impl Nodes {
    fn add(&mut self, tag: usize, p: Vec3, fields: &Fields) -> Result<(), MeshError> {
        if self.index.insert(tag, self.positions.len()).is_some() {
            return Err(fields.error(format!("node tag {tag} is defined twice")));
        }
        self.positions.push(p);
        self.tags.push(tag);
        Ok(())
    }

    fn get(&self, tag: usize, fields: &Fields) -> Result<usize, MeshError> {
        self.index
            .get(&tag)
            .copied()
            .ok_or_else(|| fields.error(format!("node tag {tag} is not defined in $Nodes")))
    }
}

fn parse(path: &Path, text: &str) -> Result<(FileNodes, Cells, RawGroups), MeshError> {
    let mut lines = Lines::new(path, text, None);
    let mut version = None;
    let mut nodes: Option<Nodes> = None;
    let mut cells: Option<Cells> = None;
    let mut groups = RawGroups::default();
    while let Some((line, header)) = lines.next_line() {
        if !header.starts_with('$') {
            return Err(lines.error(
                line,
                format!(
                    "expected a section header such as $Nodes, found `{}`",
                    excerpt(header)
                ),
            ));
        }
        let name = &header[1..];
        match (name, version) {
            ("MeshFormat", _) => version = Some(mesh_format(&mut lines)?),
            (_, None) => {
                return Err(lines.error(line, "expected $MeshFormat first: this is not a Gmsh file"))
            }
            ("Nodes", Some(v)) => nodes = Some(read_nodes(&mut lines, v)?),
            ("Elements", Some(v)) => {
                let Some(nodes) = &nodes else {
                    return Err(lines.error(line, "$Elements must come after $Nodes"));
                };
                cells = Some(read_elements(&mut lines, v, nodes, &mut groups)?);
            }
            ("PhysicalNames", _) => read_physical_names(&mut lines, &mut groups)?,
            ("Entities", Some(Version::V41)) => read_entities(&mut lines, &mut groups)?,
            _ => skip_section(&mut lines, name)?,
        }
        if !matches!(
            name,
            "MeshFormat" | "Nodes" | "Elements" | "PhysicalNames" | "Entities"
        ) || (name == "Entities" && version == Some(Version::V2))
        {
            continue;
        }
        let end = format!("$End{name}");
        let fields = lines.fields(&end)?;
        if fields.text != end {
            return Err(fields.error(format!("expected {end}, found `{}`", excerpt(fields.text))));
        }
    }
    if version.is_none() {
        return Err(lines.eof("$MeshFormat: this is not a Gmsh file"));
    }
    let (Some(nodes), Some(cells)) = (nodes, cells) else {
        return Err(lines.eof("a $Nodes and an $Elements section"));
    };
    let nodes = FileNodes {
        positions: nodes.positions,
        tags: nodes.tags,
    };
    Ok((nodes, cells, groups))
}

/// `$PhysicalNames`: `count`, then `dimension tag "name"` per line. Groups of every
/// dimension are kept (and listed even if empty); only surface and volume groups hold
/// elements, so a point or curve group is found, and a selection of it says what it is.
fn read_physical_names(lines: &mut Lines, groups: &mut RawGroups) -> Result<(), MeshError> {
    let count = lines
        .data("the number of physical names")?
        .usize("the number of physical names")?;
    for i in 0..count {
        let what = format!(
            "physical name {} of {count} (`dimension tag \"name\"`)",
            i + 1
        );
        let mut f = lines.data(&what)?;
        let dimension = f.usize("the dimension of the physical group")?;
        let tag = f.i64("the tag of the physical group")?;
        let text = f.text;
        let name = match (text.find('"'), text.rfind('"')) {
            (Some(a), Some(b)) if a < b => &text[a + 1..b],
            _ => {
                return Err(f.error(format!(
                    "expected a quoted group name, found `{}`",
                    excerpt(text)
                )))
            }
        };
        if dimension > 3 {
            return Err(f.error(format!(
                "physical group dimension {dimension}: expected 0 (points) to 3 (volumes)"
            )));
        }
        groups.names.insert((dimension, tag), name.to_string());
        groups.groups.entry((dimension, tag)).or_default();
    }
    Ok(())
}

/// `$Entities` of format 4.1: the physical tags of every entity. Points are
/// `tag x y z numPhysicalTags tags...`; curves, surfaces and volumes are
/// `tag minX minY minZ maxX maxY maxZ numPhysicalTags tags... numBounding tags...`.
fn read_entities(lines: &mut Lines, groups: &mut RawGroups) -> Result<(), MeshError> {
    let mut h = lines.data("`numPoints numCurves numSurfaces numVolumes`")?;
    let counts = [
        h.usize("numPoints")?,
        h.usize("numCurves")?,
        h.usize("numSurfaces")?,
        h.usize("numVolumes")?,
    ];
    h.end("the four entity counts")?;
    for (dimension, &count) in counts.iter().enumerate() {
        for _ in 0..count {
            let mut f = lines.data("an entity line `tag bounding-box numPhysicalTags tags...`")?;
            let tag = f.i64("entity tag")?;
            let coordinates = if dimension == 0 { 3 } else { 6 };
            for _ in 0..coordinates {
                f.f64("bounding box coordinate")?;
            }
            let n = f.usize("numPhysicalTags")?;
            let physical = (0..n)
                .map(|_| f.i64("physical tag"))
                .collect::<Result<Vec<_>, _>>()?;
            if dimension > 0 {
                let bounding = f.usize("numBoundingEntities")?;
                f.skip(bounding, "bounding entity tag")?;
            }
            f.end("the entity")?;
            groups.entities.insert((dimension, tag), physical);
        }
    }
    Ok(())
}

/// `version file-type data-size`: ASCII 2.x or 4.1 only.
fn mesh_format(lines: &mut Lines) -> Result<Version, MeshError> {
    let mut f = lines.fields("the format line `version file-type data-size`")?;
    let text = f.text;
    let version = f.f64("the format version")?;
    let file_type = f.usize("the file type (0 = ASCII)")?;
    if file_type != 0 {
        return Err(f.error(format!(
            "binary Gmsh files are not supported (`{}`): save as ASCII format 4.1 or 2.2",
            excerpt(text)
        )));
    }
    if (2.0..3.0).contains(&version) {
        Ok(Version::V2)
    } else if version == 4.1 {
        Ok(Version::V41)
    } else {
        Err(f.error(format!(
            "unsupported Gmsh format version {version}: save as ASCII format 4.1 or 2.2"
        )))
    }
}

/// Skips an unknown section up to its `$End` marker.
fn skip_section(lines: &mut Lines, name: &str) -> Result<(), MeshError> {
    let end = format!("$End{name}");
    while let Some((_, text)) = lines.next_line() {
        if text == end {
            return Ok(());
        }
    }
    Err(lines.eof(&end))
}

fn read_nodes(lines: &mut Lines, version: Version) -> Result<Nodes, MeshError> {
    let mut nodes = Nodes::default();
    let xyz = |f: &mut Fields| -> Result<Vec3, MeshError> {
        Ok(Vec3::new(
            f.f64("x coordinate")?,
            f.f64("y coordinate")?,
            f.f64("z coordinate")?,
        ))
    };
    match version {
        Version::V2 => {
            let count = lines
                .data("the number of nodes")?
                .usize("the number of nodes")?;
            for i in 0..count {
                let what = format!("node {} of {count} (`tag x y z`)", i + 1);
                let mut f = lines.data(&what)?;
                let tag = f.usize("node tag")?;
                let p = xyz(&mut f)?;
                f.end("`tag x y z`")?;
                nodes.add(tag, p, &f)?;
            }
        }
        Version::V41 => {
            let mut h = lines.data("`numEntityBlocks numNodes minNodeTag maxNodeTag`")?;
            let blocks = h.usize("numEntityBlocks")?;
            let count = h.usize("numNodes")?;
            for _ in 0..blocks {
                let mut b = lines.data("`entityDim entityTag parametric numNodesInBlock`")?;
                let dim = b.usize("entityDim")?;
                b.i64("entityTag")?;
                let parametric = b.usize("parametric (0 or 1)")?;
                let in_block = b.usize("numNodesInBlock")?;
                if dim > 3 || parametric > 1 {
                    return Err(b.error(format!(
                        "expected entityDim <= 3 and parametric 0 or 1, found `{}`",
                        excerpt(b.text)
                    )));
                }
                let mut tags = Vec::new();
                for _ in 0..in_block {
                    let mut f = lines.data("a node tag")?;
                    tags.push(f.usize("node tag")?);
                    f.end("the node tag")?;
                }
                for tag in tags {
                    let mut f = lines.data("node coordinates `x y z`")?;
                    let p = xyz(&mut f)?;
                    f.skip(parametric * dim, "parametric coordinates")?;
                    f.end("the node coordinates")?;
                    nodes.add(tag, p, &f)?;
                }
            }
            if nodes.positions.len() != count {
                return Err(lines.error(
                    lines.last,
                    format!(
                        "the header declares {count} nodes but the blocks hold {}",
                        nodes.positions.len()
                    ),
                ));
            }
        }
    }
    Ok(nodes)
}

/// The tet of Gmsh element type `kind`, if it is one.
fn tet_type(kind: usize) -> Option<TetElement> {
    match kind {
        4 => Some(TetElement::Tet4),
        11 => Some(TetElement::Tet10),
        _ => None,
    }
}

/// Name of a Gmsh volume element type other than the 4- and 10-node tets, or `None` for
/// points, lines, triangles and quads (which are skipped).
fn rejected_volume_type(kind: usize) -> Option<&'static str> {
    Some(match kind {
        5 => "8-node hexahedron",
        6 => "6-node prism",
        7 => "5-node pyramid",
        12 => "27-node hexahedron",
        13 => "18-node prism",
        14 => "14-node pyramid",
        17 => "20-node hexahedron",
        18 => "15-node prism",
        19 => "13-node pyramid",
        29 => "20-node tetrahedron",
        30 => "35-node tetrahedron",
        31 => "56-node tetrahedron",
        92 => "64-node hexahedron",
        93 => "125-node hexahedron",
        _ => return None,
    })
}

/// Gmsh types of points, lines, triangles and quads (first to third order, complete and
/// serendipity), which carry no volume and are skipped.
fn is_lower_dimensional(kind: usize) -> bool {
    matches!(kind, 1..=3 | 8..=10 | 15 | 16 | 20..=28 | 36 | 37)
}

fn reject(f: &Fields, kind: usize) -> MeshError {
    let name = rejected_volume_type(kind).map_or_else(
        || format!("unknown element type {kind}"),
        |n| format!("element type {kind} ({n})"),
    );
    f.error(format!(
        "{name} is not supported: isochor reads 4-node (type 4) and 10-node (type 11) tetrahedra"
    ))
}

/// Reads the nodes of one tet of `kind` into `cells`; the first tet fixes the kind of all.
fn read_tet(
    f: &mut Fields,
    tag: usize,
    kind: TetElement,
    nodes: &Nodes,
    cells: &mut Option<Cells>,
) -> Result<(), MeshError> {
    let cells = cells.get_or_insert_with(|| Cells {
        kind,
        connectivity: Vec::new(),
        tags: Vec::new(),
        lines: Vec::new(),
    });
    if cells.kind != kind {
        return Err(f.error(format!(
            "a {}-node tetrahedron in a file of {}-node ones (the first is on line {}): mixed orders are not supported",
            kind.num_nodes(),
            cells.kind.num_nodes(),
            cells.lines[0]
        )));
    }
    let n = kind.num_nodes();
    for a in 0..n {
        let tag = f.usize(&format!("node {} of the {n}-node tetrahedron", a + 1))?;
        cells.connectivity.push(nodes.get(tag, f)?);
    }
    f.end(&format!("the {n} nodes of the tetrahedron"))?;
    cells.tags.push(tag);
    cells.lines.push(f.line);
    Ok(())
}

/// Number of nodes of a Gmsh triangle type (3-node type 2, 6-node type 9).
fn triangle_nodes(kind: usize) -> Option<usize> {
    match kind {
        2 => Some(3),
        9 => Some(6),
        _ => None,
    }
}

/// The corners (file node indices) of an `n`-node triangle's remaining fields.
fn read_triangle(f: &mut Fields, n: usize, nodes: &Nodes) -> Result<[usize; 3], MeshError> {
    let mut corners = [0; 3];
    for a in 0..n {
        let tag = f.usize(&format!("node {} of the {n}-node triangle", a + 1))?;
        let index = nodes.get(tag, f)?;
        if let Some(c) = corners.get_mut(a) {
            *c = index;
        }
    }
    f.end(&format!("the {n} nodes of the triangle"))?;
    Ok(corners)
}

/// The tets of a format 2.2 file by their nodes: Gmsh 2.2 writes an element of several
/// physical groups once per group, each line with one group's tag; the lines of one element
/// (the same nodes in the same order) are read as one tet in all their groups, as format 4.1
/// (one line, the entity's several physical tags) says it.
#[derive(Default)]
struct Repeats {
    /// The first tet of each sequence of corners.
    first: HashMap<[usize; 4], usize>,
}

impl Repeats {
    /// The index of tet `index`, just read into `cells`: its own, or if it repeats an earlier
    /// tet's nodes, that tet's (and the repeat is removed from `cells`).
    fn merge(&mut self, cells: &mut Option<Cells>, index: usize) -> usize {
        let Some(cells) = cells.as_mut() else {
            return index;
        };
        let n = cells.kind.num_nodes();
        let nodes = &cells.connectivity[index * n..];
        let corners = [nodes[0], nodes[1], nodes[2], nodes[3]];
        match self.first.get(&corners) {
            Some(&first) if cells.connectivity[first * n..(first + 1) * n] == *nodes => {
                cells.connectivity.truncate(index * n);
                cells.tags.truncate(index);
                cells.lines.truncate(index);
                first
            }
            _ => {
                self.first.entry(corners).or_insert(index);
                index
            }
        }
    }
}

/// The physical tag of a format 2.2 element line (its first tag; 0 if it has none), after
/// which the other tags are skipped.
fn v2_physical_tag(f: &mut Fields) -> Result<i64, MeshError> {
    let ntags = f.usize("number of tags")?;
    if ntags == 0 {
        return Ok(0);
    }
    let physical = f.i64("the physical tag")?;
    f.skip(ntags - 1, "an element tag")?;
    Ok(physical)
}

fn read_elements(
    lines: &mut Lines,
    version: Version,
    nodes: &Nodes,
    groups: &mut RawGroups,
) -> Result<Cells, MeshError> {
    let mut cells = None;
    let next_tet = |cells: &Option<Cells>| cells.as_ref().map_or(0, |c: &Cells| c.tags.len());
    match version {
        Version::V2 => {
            let mut once_per_element = Repeats::default();
            let count = lines
                .data("the number of elements")?
                .usize("the number of elements")?;
            for i in 0..count {
                let what = format!(
                    "element {} of {count} (`tag type ntags tags... nodes...`)",
                    i + 1
                );
                let mut f = lines.data(&what)?;
                let tag = f.usize("element tag")?;
                let kind = f.usize("element type")?;
                if let Some(tet) = tet_type(kind) {
                    let physical = v2_physical_tag(&mut f)?;
                    let index = next_tet(&cells);
                    read_tet(&mut f, tag, tet, nodes, &mut cells)?;
                    let index = once_per_element.merge(&mut cells, index);
                    groups.add_tet(&[physical], index);
                } else if let Some(n) = triangle_nodes(kind) {
                    let physical = v2_physical_tag(&mut f)?;
                    let face = read_triangle(&mut f, n, nodes)?;
                    groups.add_face(&[physical], face, f.line);
                } else if !is_lower_dimensional(kind) {
                    return Err(reject(&f, kind));
                }
            }
        }
        Version::V41 => {
            let mut h = lines.data("`numEntityBlocks numElements minElementTag maxElementTag`")?;
            let blocks = h.usize("numEntityBlocks")?;
            let count = h.usize("numElements")?;
            let mut seen = 0usize;
            for _ in 0..blocks {
                let mut b = lines.data("`entityDim entityTag elementType numElementsInBlock`")?;
                let dim = b.usize("entityDim")?;
                let entity = b.i64("entityTag")?;
                let kind = b.usize("elementType")?;
                let in_block = b.usize("numElementsInBlock")?;
                let tet = tet_type(kind).filter(|_| dim == 3);
                if dim == 3 && tet.is_none() {
                    return Err(reject(&b, kind));
                }
                let triangle = triangle_nodes(kind).filter(|_| dim == 2);
                let physical = groups
                    .entities
                    .get(&(dim, entity))
                    .cloned()
                    .unwrap_or_default();
                for _ in 0..in_block {
                    let mut f = lines.data("an element line `tag node...`")?;
                    if let Some(tet) = tet {
                        let tag = f.usize("element tag")?;
                        let index = next_tet(&cells);
                        read_tet(&mut f, tag, tet, nodes, &mut cells)?;
                        groups.add_tet(&physical, index);
                    } else if let Some(n) = triangle {
                        f.usize("element tag")?;
                        let face = read_triangle(&mut f, n, nodes)?;
                        groups.add_face(&physical, face, f.line);
                    }
                }
                seen = seen.saturating_add(in_block);
            }
            if seen != count {
                return Err(lines.error(
                    lines.last,
                    format!("the header declares {count} elements but the blocks hold {seen}"),
                ));
            }
        }
    }
    // A tet listed twice in one group (a repeated 2.2 line) is in it once.
    for group in groups.groups.values_mut() {
        group.tets.sort_unstable();
        group.tets.dedup();
    }
    Ok(cells.unwrap_or(Cells {
        kind: TetElement::Tet4,
        connectivity: Vec::new(),
        tags: Vec::new(),
        lines: Vec::new(),
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Result<TetMesh, MeshError> {
        let path = Path::new("t.msh");
        let (nodes, cells, _) = parse(path, text)?;
        linear(path, nodes, cells)
    }

    fn err(text: &str) -> (usize, String) {
        match read(text) {
            Err(MeshError::Parse {
                path,
                line,
                message,
            }) => {
                assert_eq!(path, Path::new("t.msh"));
                (line, message)
            }
            other => panic!("expected a parse error, got {other:?}"),
        }
    }

    const V2: &str = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n5\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n9 5 5 5\n$EndNodes\n$Elements\n2\n1 2 2 1 1 1 2 3\n2 4 2 1 1 1 2 3 4\n$EndElements\n";

    #[test]
    fn minimal_v2_file() {
        let mesh = read(V2).unwrap();
        assert_eq!(mesh.num_vertices(), 4, "the unused node 9 is dropped");
        assert_eq!(mesh.num_tets(), 1);
        assert!((mesh.rest_volume() - 1.0 / 6.0).abs() < 1e-15);
    }

    #[test]
    fn malformed_v2_files_name_the_line() {
        let (line, m) = err(&V2.replace("2.2 0 8", "2.2 1 8"));
        assert_eq!(line, 2);
        assert!(m.contains("binary"), "{m}");
        let (line, m) = err(&V2.replace("3 0 1 0", "3 0 nan 0"));
        assert_eq!(line, 8);
        assert!(m.contains("finite y coordinate"), "{m}");
        let (line, m) = err(&V2.replace("1 1 2 3 4", "1 1 2 3 7"));
        assert_eq!(line, 15);
        assert!(m.contains("node tag 7 is not defined"), "{m}");
        let (line, m) = err(&V2.replace("2 4 2 1 1", "2 5 2 1 1"));
        assert_eq!(line, 15);
        assert!(m.contains("8-node hexahedron"), "{m}");
        let (line, m) = err(&V2.replace("2 4 2 1 1", "2 11 2 1 1"));
        assert_eq!(line, 15);
        assert!(m.contains("node 5 of the 10-node tetrahedron"), "{m}");
        let (line, m) = err(&V2.replace("$Elements\n2\n", "$Elements\n3\n"));
        assert_eq!(line, 16);
        assert!(m.contains("element 3 of 3"), "{m}");
        let (line, m) = err(&V2[..V2.find("4 0 0 1").unwrap()]);
        assert_eq!(line, 9);
        assert!(
            m.contains("unexpected end of file") && m.contains("node 4 of 5"),
            "{m}"
        );
        // Elements and nodes are named by their tags in the file, not by internal indices.
        let (line, m) = err(&V2.replace("1 1 2 3 4", "1 1 2 3 3"));
        assert_eq!(line, 15);
        assert!(
            m.contains("tet 2: vertex 3 appears more than once in [1, 2, 3, 3]")
                && m.contains("numbered as in the file"),
            "{m}"
        );
        let (line, m) = err(&V2.replace("4 0 0 1", "4 1 1 0"));
        assert_eq!(line, 15);
        assert!(m.contains("tet 2 is degenerate"), "{m}");
        // Garbage is escaped and cut, not echoed raw.
        let garbage = format!("\u{1b}[31m{}\n", "x".repeat(500));
        let (_, m) = err(&garbage);
        assert!(
            m.contains("`\\u{1b}[31mxxx") && m.contains("... (505 characters)`"),
            "{m}"
        );
        assert!(m.len() < 200, "{m}");
        let (_, m) = err(&V2.replace("5\n1 0 0 0", "99999999999999999999999\n1 0 0 0"));
        assert!(m.contains("number of nodes"), "{m}");
        let (line, m) = err("hello\n");
        assert_eq!(line, 1);
        assert!(m.contains("section header"), "{m}");
        let (_, m) = err("$MeshFormat\n3.0 0 8\n$EndMeshFormat\n");
        assert!(m.contains("version 3"), "{m}");
    }

    /// One 10-node tet over the unit tet's corners, listed negatively oriented (corners 1 3 2
    /// 4) with its mid-edge nodes in Gmsh's order for that listing, plus a 6-node triangle.
    const V2_TET10: &str = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n10\n\
        1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n\
        12 0.5 0 0\n13 0 0.5 0\n14 0 0 0.5\n23 0.5 0.5 0\n24 0.5 0 0.5\n34 0 0.5 0.5\n\
        $EndNodes\n$Elements\n2\n\
        1 9 2 1 1 1 2 3 12 23 13\n\
        2 11 2 1 1 1 3 2 4 13 23 12 14 24 34\n$EndElements\n";

    #[test]
    fn ten_node_v2_file_reads_reoriented() {
        let path = Path::new("t.msh");
        let (nodes, cells, _) = parse(path, V2_TET10).unwrap();
        let mesh = assemble(path, nodes, cells).unwrap();
        assert_eq!(mesh.kind(), TetElement::Tet10);
        assert_eq!((mesh.num_vertices(), mesh.num_nodes()), (4, 10));
        assert_eq!(mesh.corners().reoriented(), 1);
        assert!((mesh.rest_volume() - 1.0 / 6.0).abs() < 1e-15);
        // Every mid-edge node sits at the midpoint of its local edge after re-orientation.
        let x = mesh.nodes();
        let element = mesh.element(0);
        for (k, [a, b]) in crate::element::TET_EDGES.into_iter().enumerate() {
            let midpoint = 0.5 * (x[element[a]] + x[element[b]]);
            assert_eq!(x[element[4 + k]], midpoint, "edge {k}");
        }
        // The linear reader refuses the file at the tet's line; a mixed file is refused too.
        let (line, m) = err(V2_TET10);
        assert_eq!(line, 20);
        assert!(m.contains("read_gmsh_elements"), "{m}");
        let mixed = V2_TET10
            .replace("$Elements\n2\n", "$Elements\n3\n")
            .replace("$EndElements", "3 4 2 1 1 1 2 3 4\n$EndElements");
        let (line, m) = err(&mixed);
        assert_eq!(line, 21);
        assert!(m.contains("4-node tetrahedron in a file of 10-node"), "{m}");
        // A mid-edge node that is a corner elsewhere, or on two edges, names the element.
        let shared = mixed.replace("3 4 2 1 1 1 2 3 4", "3 4 2 1 1 12 2 3 4");
        let shared = shared
            .replace("3 4 2 1 1 12", "3 11 2 1 1 12")
            .replace("12 2 3 4\n", "12 2 3 4 1 23 13 14 24 34\n");
        let (nodes, cells, _) = parse(path, &shared).unwrap();
        match assemble(path, nodes, cells) {
            Err(MeshError::Parse { line, message, .. }) => {
                assert_eq!(line, 20);
                assert!(
                    message.contains(
                        "element 2: node 12 is a mid-edge node here and a corner of element 3"
                    ),
                    "{message}"
                );
            }
            other => panic!("expected a parse error, got {other:?}"),
        }
        let doubled = V2_TET10.replace("13 23 12 14 24 34", "13 23 12 14 23 34");
        let (nodes, cells, _) = parse(path, &doubled).unwrap();
        match assemble(path, nodes, cells) {
            Err(MeshError::Parse { line, message, .. }) => {
                assert_eq!(line, 20);
                assert!(message.contains("lies on edge"), "{message}");
            }
            other => panic!("expected a parse error, got {other:?}"),
        }
    }

    const V41: &str = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n2 4 1 4\n0 1 0 1\n1\n0 0 0\n3 1 0 3\n2\n3\n4\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n$Elements\n2 2 1 2\n2 1 2 1\n1 1 2 3\n3 1 4 1\n2 1 2 3 4\n$EndElements\n";

    #[test]
    fn minimal_v41_file_and_its_errors() {
        let mesh = read(V41).unwrap();
        assert_eq!((mesh.num_vertices(), mesh.num_tets()), (4, 1));
        let (line, m) = err(&V41.replace("3 1 4 1", "3 1 5 1"));
        assert_eq!(line, 21);
        assert!(m.contains("element type 5"), "{m}");
        let (line, m) = err(&V41.replace("2 2 1 2\n", "2 3 1 2\n"));
        assert_eq!(line, 22);
        assert!(m.contains("declares 3 elements"), "{m}");
        let (line, m) = err(&V41.replace("0 0 1\n$EndNodes", "0 0 1\n7 7 7\n$EndNodes"));
        assert_eq!(line, 16);
        assert!(m.contains("expected $EndNodes, found `7 7 7`"), "{m}");
        let (line, m) = err(&V41.replace("2 4 1 4\n", "2 5 1 4\n"));
        assert_eq!(line, 15);
        assert!(m.contains("declares 5 nodes"), "{m}");
        let (line, m) = err(&V41.replace("3 1 0 3\n", "3 1 0 4\n"));
        assert_eq!(line, 13);
        assert!(m.contains("extra field"), "{m}");
    }
}
