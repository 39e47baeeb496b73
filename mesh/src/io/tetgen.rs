//! TetGen `.node` / `.ele` reader: 0- or 1-based indices (TetGen's `-z` switch), attributes
//! and boundary markers tolerated, `#` comments skipped; the region attribute of the tets
//! (TetGen's `-A` switch, the first tet attribute) read as volume groups.

use super::text::{excerpt, Lines};
use super::{assemble, read_text, Cells, FileNodes};
use crate::element::TetElement;
use crate::{MeshError, PhysicalGroup, PhysicalGroups, TetMesh, Vec3};
use std::path::Path;

/// Reads a TetGen mesh from `path` with extension `.node` or `.ele` (or none): both
/// `stem.node` and `stem.ele` are read. The index base (0 or 1) is that of the first node;
/// the `.ele` file uses the same base, as TetGen writes them. Vertices that no tet uses are
/// dropped.
pub fn read_tetgen(path: impl AsRef<Path>) -> Result<TetMesh, MeshError> {
    Ok(read_tetgen_with_regions(path)?.0)
}

/// [`read_tetgen`], with the region attribute of every tet (the first attribute of the `.ele`
/// file, which TetGen's `-A` switch writes) as volume groups named by their number, so that
/// a scene selects `physical = "2"` as on a Gmsh mesh. No groups when the `.ele` file has no
/// attributes.
///
/// Errors: those of [`read_tetgen`]; a region attribute that is not an integer.
pub fn read_tetgen_with_regions(
    path: impl AsRef<Path>,
) -> Result<(TetMesh, PhysicalGroups), MeshError> {
    let path = path.as_ref();
    let node_path = path.with_extension("node");
    let ele_path = path.with_extension("ele");
    let (positions, base) = parse_node(&node_path, &read_text(&node_path)?)?;
    let (cells, regions) = parse_ele(&ele_path, &read_text(&ele_path)?, base, positions.len())?;
    let mesh = assemble(&ele_path, numbered(positions, base), cells)?.into_corners();
    let mut groups: std::collections::BTreeMap<i64, Vec<usize>> = Default::default();
    for (tet, region) in regions.into_iter().enumerate() {
        groups.entry(region).or_default().push(tet);
    }
    let groups = groups
        .into_iter()
        .map(|(tag, tets)| PhysicalGroup {
            dimension: 3,
            tag,
            name: None,
            faces: Vec::new(),
            tets,
        })
        .collect();
    Ok((mesh, PhysicalGroups::new(groups)))
}

/// The nodes with their indices in the file (from `base`).
fn numbered(positions: Vec<Vec3>, base: usize) -> FileNodes {
    FileNodes {
        tags: (base..base + positions.len()).collect(),
        positions,
    }
}

/// `n dim attributes markers`, then `index x y z [attributes] [marker]` per node. Returns the
/// positions and the index base.
fn parse_node(path: &Path, text: &str) -> Result<(Vec<Vec3>, usize), MeshError> {
    let mut lines = Lines::new(path, text, Some('#'));
    let mut h = lines.fields("the header `<#points> <dimension> <#attributes> <#markers>`")?;
    let count = h.usize("the number of points")?;
    let dim = h.usize("the dimension")?;
    let attributes = h.usize("the number of attributes")?;
    let markers = h.usize("the number of boundary markers (0 or 1)")?;
    if dim != 3 || markers > 1 {
        return Err(h.error(format!(
            "expected dimension 3 and 0 or 1 boundary markers, found `{}`",
            excerpt(h.text)
        )));
    }
    let mut positions = Vec::new();
    let mut base = 0;
    for i in 0..count {
        let mut f = lines.fields(&format!("point {} of {count}", i + 1))?;
        let index = f.usize("the point index")?;
        if i == 0 {
            if index > 1 {
                return Err(f.error(format!(
                    "the first point index must be 0 or 1, found {index}"
                )));
            }
            base = index;
        } else if index != base + i {
            return Err(f.error(format!("expected point index {}, found {index}", base + i)));
        }
        positions.push(Vec3::new(
            f.f64("x coordinate")?,
            f.f64("y coordinate")?,
            f.f64("z coordinate")?,
        ));
        f.skip(attributes, "a point attribute")?;
        f.skip(markers, "the boundary marker")?;
        f.end("the point's coordinates, attributes and marker")?;
    }
    if let Some((line, text)) = lines.next_line() {
        return Err(lines.error(
            line,
            format!(
                "expected end of file after {count} points, found `{}`",
                excerpt(text)
            ),
        ));
    }
    Ok((positions, base))
}

/// `n nodes-per-tet attributes`, then `index v0 v1 v2 v3 [attributes]` per tet; with the
/// first attribute of every tet (its region) if there are attributes.
fn parse_ele(
    path: &Path,
    text: &str,
    base: usize,
    points: usize,
) -> Result<(Cells, Vec<i64>), MeshError> {
    let mut lines = Lines::new(path, text, Some('#'));
    let mut h = lines.fields("the header `<#tetrahedra> <nodes per tetrahedron> <#attributes>`")?;
    let count = h.usize("the number of tetrahedra")?;
    let per_tet = h.usize("the number of nodes per tetrahedron")?;
    let attributes = h.usize("the number of attributes")?;
    if per_tet != 4 {
        return Err(h.error(format!(
            "{per_tet}-node tetrahedra are not supported: isochor reads linear (4-node) tetrahedra only"
        )));
    }
    let mut connectivity = Vec::new();
    let mut tags = Vec::new();
    let mut tet_lines = Vec::new();
    let mut regions = Vec::new();
    for i in 0..count {
        let mut f = lines.fields(&format!("tetrahedron {} of {count}", i + 1))?;
        let index = f.usize("the tetrahedron index")?;
        if index != base + i {
            return Err(f.error(format!(
                "expected tetrahedron index {}, found {index}",
                base + i
            )));
        }
        let mut tet = [0; 4];
        for (a, slot) in tet.iter_mut().enumerate() {
            let v = f.usize(&format!("node {} of the tetrahedron", a + 1))?;
            *slot = v.checked_sub(base).filter(|&v| v < points).ok_or_else(|| {
                f.error(format!(
                    "node index {v} is out of range: the .node file defines {base}..={}",
                    (base + points).saturating_sub(1)
                ))
            })?;
        }
        if attributes > 0 {
            let region = f.f64("the region attribute")?;
            if region.fract() != 0.0 || region.abs() > 1e15 {
                return Err(f.error(format!("the region attribute {region} is not an integer")));
            }
            regions.push(region as i64);
            f.skip(attributes - 1, "a tetrahedron attribute")?;
        }
        f.end("the tetrahedron's nodes and attributes")?;
        connectivity.extend(tet);
        tags.push(index);
        tet_lines.push(f.line);
    }
    if let Some((line, text)) = lines.next_line() {
        return Err(lines.error(
            line,
            format!(
                "expected end of file after {count} tetrahedra, found `{}`",
                excerpt(text)
            ),
        ));
    }
    Ok((
        Cells {
            kind: TetElement::Tet4,
            connectivity,
            tags,
            lines: tet_lines,
        },
        regions,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    const NODE: &str =
        "# unit tet\n4 3 1 1\n1 0 0 0 0.5 1\n2 1 0 0 0.5 1\n3 0 1 0 0.5 1\n4 0 0 1 0.5 1\n";
    const ELE: &str = "1 4 1\n1 1 2 3 4 7 # region 7\n";

    fn parse_pair(node: &str, ele: &str) -> Result<TetMesh, MeshError> {
        let (x, base) = parse_node(Path::new("t.node"), node)?;
        let (cells, _) = parse_ele(Path::new("t.ele"), ele, base, x.len())?;
        Ok(assemble(Path::new("t.ele"), numbered(x, base), cells)?.into_corners())
    }

    fn err(node: &str, ele: &str) -> (String, usize, String) {
        match parse_pair(node, ele) {
            Err(MeshError::Parse {
                path,
                line,
                message,
            }) => (path.display().to_string(), line, message),
            other => panic!("expected a parse error, got {other:?}"),
        }
    }

    #[test]
    fn one_and_zero_based_files() {
        let mesh = parse_pair(NODE, ELE).unwrap();
        assert!((mesh.rest_volume() - 1.0 / 6.0).abs() < 1e-15);
        let zero_node = "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n";
        let mesh = parse_pair(zero_node, "1 4 0\n0 0 2 1 3\n").unwrap();
        assert_eq!(mesh.reoriented(), 1);
    }

    #[test]
    fn malformed_files_name_the_file_and_line() {
        assert_eq!(
            err(NODE, "1 4 1\n1 1 2 3 5 7\n"),
            (
                "t.ele".into(),
                2,
                "node index 5 is out of range: the .node file defines 1..=4".into()
            )
        );
        let (path, line, m) = err(&NODE.replace("3 0 1 0", "3 0 NaN 0"), ELE);
        assert_eq!((path.as_str(), line), ("t.node", 5));
        assert!(m.contains("finite y coordinate"), "{m}");
        let (path, line, m) = err(&NODE[..NODE.find("4 0 0 1").unwrap()], ELE);
        assert_eq!((path.as_str(), line), ("t.node", 6));
        assert!(
            m.contains("unexpected end of file: expected point 4 of 4"),
            "{m}"
        );
        let (path, line, m) = err(NODE, "1 10 0\n");
        assert_eq!((path.as_str(), line), ("t.ele", 1));
        assert!(m.contains("10-node"), "{m}");
        let (_, line, m) = err(NODE, "1 4 1\n1 1 2 3 3 7\n");
        assert_eq!(line, 2);
        assert!(
            m.contains("tet 1: vertex 3 appears more than once in [1, 2, 3, 3]"),
            "{m}"
        );
        let (_, line, m) = err(NODE, "1 4 1\n1 1 2 3\n");
        assert_eq!(line, 2);
        assert!(m.contains("expected node 4 of the tetrahedron"), "{m}");
        let (_, line, m) = err(NODE, "2 4 1\n1 1 2 3 4 0\n");
        assert_eq!(line, 3);
        assert!(m.contains("tetrahedron 2 of 2"), "{m}");
        let (_, line, m) = err(&NODE.replace("\n3 0", "\n7 0"), ELE);
        assert_eq!(line, 5);
        assert!(m.contains("expected point index 3"), "{m}");
        let (_, line, m) = err(NODE, "1 4 1\n1 1 2 3 4 7\n2 1 2 3 4 7\n");
        assert_eq!(line, 3);
        assert!(m.contains("expected end of file"), "{m}");
    }
}
