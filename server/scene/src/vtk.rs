//! VTK unstructured grids (XML `.vtu`, legacy `.vtk`) as meshes with named regions (issue 34),
//! read through the `vtkio` crate, and their conversion to Gmsh MSH 4.1 ([`write_msh41`]).
//!
//! What is read: one unstructured-grid piece, its points and cells, and an integer cell-data
//! array of labels (by default the first of [`DEFAULT_LABEL_ARRAYS`] the file has). A
//! [`LabelMap`] names the labels. In 3D linear tetrahedra (VTK type 10) are the elements and
//! labelled triangles (type 5) boundary faces; in 2D triangles are the elements (the points in
//! a plane z = const) and labelled lines (type 3) boundary edges. A label of elements is a
//! region, a label of boundary faces or edges a boundary set (the nodes of its faces), named by
//! the map as Gmsh's physical groups are. Nodes used by no element are dropped (the others keep
//! the file's order) and regions are ordered by label, as `needlesim_core::msh` does, so a mesh
//! written by meshio from a `.msh` file reads to the same mesh.
//!
//! Text only: XML with `ascii` or `binary` (base64) data arrays, uncompressed, or an ASCII
//! legacy file. Compressed or raw-appended XML and binary legacy files are refused with the way
//! to write them as text (the bytes of a scene's files travel as text, over the API too).
//!
//! Refused, each naming the problem: a malformed file; another dataset type; cell types other
//! than those above, or elements of both dimensions; no label array, a label array that is not
//! one integer per cell; a label of the file missing from the map or a label of the map on no
//! cell (an empty region); two labels of one name; an inverted (3D) or degenerate element.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use anyhow::{Context, Result, bail};
use needlesim_core::d3::mesh::{DEGENERATE_VOLUME_TOL, longest_edge_m, signed_volume_m3};
use needlesim_core::d3::{TetMesh, TetMeshLimits};
use needlesim_core::{Mesh, MeshLimits};
use vtkio::model::{Attribute, CellType, DataSet, IOBuffer, Piece, VertexNumbers};

use crate::limit;

/// The cell-data arrays tried for the labels, in order, when none is named: Gmsh's (as meshio
/// writes it), Slicer's SegmentMesher's, and two plain names.
pub const DEFAULT_LABEL_ARRAYS: [&str; 4] = ["gmsh:physical", "CellEntityIds", "labels", "region"];

/// Deepest XML element nesting accepted before parsing (a VTU file nests 5 levels; the bound
/// keeps the XML deserialiser's recursion small whatever the input).
const MAX_XML_DEPTH: usize = 32;

/// The names of a file's integer labels: `1=tissue,2=lesion` on the command line, `labels = { 1 =
/// "tissue", 2 = "lesion" }` in a scene. Ordered by label.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LabelMap(pub BTreeMap<i64, String>);

impl LabelMap {
    /// From `1=tissue,2=lesion`; errors name the bad entry.
    pub fn parse_list(text: &str) -> Result<Self> {
        let mut map = BTreeMap::new();
        for entry in text.split(',').map(str::trim).filter(|e| !e.is_empty()) {
            let Some((label, name)) = entry.split_once('=') else {
                bail!("labels: '{}' is not LABEL=NAME (e.g. 1=tissue,2=lesion)", limit::quote(entry));
            };
            Self::insert(&mut map, label.trim(), name.trim())?;
        }
        Ok(Self(map))
    }

    /// From a scene's `labels` table (keys are the labels, as strings in TOML).
    pub fn from_table(table: &BTreeMap<String, String>) -> Result<Self> {
        let mut map = BTreeMap::new();
        for (label, name) in table {
            Self::insert(&mut map, label.trim(), name)?;
        }
        Ok(Self(map))
    }

    fn insert(map: &mut BTreeMap<i64, String>, label: &str, name: &str) -> Result<()> {
        let Ok(l) = label.parse::<i64>() else {
            bail!("labels: '{}' is not an integer label", limit::quote(label));
        };
        needlesim_core::sim::param_limits::check_name(&format!("labels: label {l}"), name).map_err(anyhow::Error::msg)?;
        if let Some((other, _)) = map.iter().find(|(_, n)| *n == name) {
            bail!("labels: labels {other} and {l} are both named '{}'; give each label its own name", limit::quote(name));
        }
        if map.insert(l, name.to_owned()).is_some() {
            bail!("labels: label {l} is given twice");
        }
        Ok(())
    }

    fn list(&self) -> String {
        self.0.iter().map(|(l, n)| format!("{l}={n}")).collect::<Vec<_>>().join(",")
    }
}

/// How to read a VTK file's regions.
#[derive(Debug, Clone, Default)]
pub struct VtkOptions {
    /// Names of the labels (required: every label of the file must be named).
    pub labels: LabelMap,
    /// The cell-data array holding the labels; `None`: the first of [`DEFAULT_LABEL_ARRAYS`].
    pub label_array: Option<String>,
}

/// A labelled simplex mesh read from a VTK file: elements of `dim` + 1 nodes (triangles or
/// tetrahedra), boundary cells of `dim` nodes (lines or triangles).
#[derive(Debug, Clone, PartialEq)]
pub struct VtkMesh {
    /// 2 or 3.
    pub dim: usize,
    /// Node coordinates, m (z of a 2D mesh: the plane's).
    pub nodes_m: Vec<[f64; 3]>,
    /// Elements, `dim + 1` node indices each.
    pub elements: Vec<Vec<usize>>,
    /// The region index of each element.
    pub region_of_element: Vec<usize>,
    /// Region names and labels, by increasing label.
    pub regions: Vec<(i64, String)>,
    /// Boundary cells (`dim` node indices) by set: (label, name, cells), by increasing label.
    pub boundary: Vec<(i64, String, Vec<Vec<usize>>)>,
    /// The label array read.
    pub label_array: String,
}

/// Reads a VTK unstructured grid from its text; `dim` (2 or 3) is the dimension of the elements
/// wanted.
pub fn read_vtk(text: &str, dim: usize, opts: &VtkOptions) -> Result<VtkMesh> {
    assert!(dim == 2 || dim == 3, "dim must be 2 or 3");
    from_piece(parse_piece(text)?, dim, opts)
}

/// Reads a VTK unstructured grid of either dimension: 3D when it holds tetrahedra, else 2D.
pub fn read_vtk_any(text: &str, opts: &VtkOptions) -> Result<VtkMesh> {
    let piece = parse_piece(text)?;
    let dim = if piece.cells.types.contains(&CellType::Tetra) { 3 } else { 2 };
    from_piece(piece, dim, opts)
}

/// A mesh file's kind, from its name: what the `mesh` command reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshInput {
    /// `.vtu` or `.vtk`.
    Vtk,
    /// `.nii`, `.nii.gz`, `.nrrd`, `.nhdr`: a labelmap volume (not yet meshed here).
    Labelmap,
}

impl MeshInput {
    /// The kind of `file_name`, or an error naming the supported extensions.
    pub fn of(file_name: &str) -> Result<Self> {
        let lower = file_name.to_ascii_lowercase();
        if lower.ends_with(".vtu") || lower.ends_with(".vtk") {
            Ok(Self::Vtk)
        } else if [".nii", ".nii.gz", ".nrrd", ".nhdr"].iter().any(|e| lower.ends_with(e)) {
            Ok(Self::Labelmap)
        } else {
            bail!("'{}': the input must be a VTK mesh (.vtu, .vtk) or a labelmap (.nii, .nii.gz, .nrrd)", limit::quote(file_name))
        }
    }
}

/// Whether the `mesh` command reads `file_name` (by its extension), before the file is opened:
/// an error naming the supported kinds otherwise, or saying that labelmaps are not yet meshed.
pub fn check_mesh_input(file_name: &str) -> Result<()> {
    match MeshInput::of(file_name)? {
        MeshInput::Labelmap => bail!(
            "'{}': labelmaps (NIfTI, NRRD) are not yet supported; mesh the segmentation to a .vtu first (e.g. 3D Slicer's SegmentMesher)",
            limit::quote(file_name)
        ),
        MeshInput::Vtk => Ok(()),
    }
}

/// What [`convert_to_msh`] made: the mesh read and its MSH 4.1 text.
pub struct Converted {
    pub mesh: VtkMesh,
    pub msh: String,
}

/// The `mesh` command's conversion: an input file's text (named `file_name`, whose extension
/// chooses the reader) to Gmsh MSH 4.1 with physical groups named by the labels, checked by
/// reading it back with needlesim's own reader (same regions, measures to 1e-9 relative).
pub fn convert_to_msh(file_name: &str, text: &str, opts: &VtkOptions) -> Result<Converted> {
    check_mesh_input(file_name)?;
    let mesh = read_vtk_any(text, opts)?;
    let msh = write_msh41(&mesh);
    // Read back: the same regions with the same measures, the same boundary sets.
    let (names, measures, sets): (Vec<String>, Vec<f64>, BTreeMap<String, Vec<usize>>) = if mesh.dim == 3 {
        let limits = TetMeshLimits::default();
        mesh.to_tet_mesh(&limits).context("the mesh read")?;
        let m = needlesim_core::msh::parse_msh3d(&msh, &limits).context("reading the written MSH back")?.mesh;
        let mut v = vec![0.0; m.region_names().len()];
        for (t, &r) in m.tets().iter().zip(m.region_of_tet()) {
            let p = t.map(|i| m.nodes_m()[i]);
            v[r] += signed_volume_m3(p[0], p[1], p[2], p[3]).abs();
        }
        (m.region_names().to_vec(), v, m.boundary_sets().clone())
    } else {
        let limits = MeshLimits::default();
        mesh.to_tri_mesh(&limits).context("the mesh read")?;
        let m = needlesim_core::msh::parse_msh(&msh, &limits).context("reading the written MSH back")?.mesh;
        let mut a = vec![0.0; m.region_names().len()];
        for (t, &r) in m.triangles().iter().zip(m.region_of_tri()) {
            let p = t.map(|i| m.nodes_m()[i]);
            a[r] += 0.5 * ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0])).abs();
        }
        (m.region_names().to_vec(), a, m.boundary_sets().clone())
    };
    if names != mesh.region_names() {
        bail!("the written MSH reads back with regions {names:?}, not {:?}", mesh.region_names());
    }
    for ((name, a), b) in names.iter().zip(&measures).zip(mesh.region_measures()) {
        if (a - b).abs() > 1e-9 * b.abs().max(f64::MIN_POSITIVE) {
            bail!("the written MSH's region '{name}' measures {a:e}, not {b:e}");
        }
    }
    if sets != mesh.boundary_sets() {
        bail!("the written MSH reads back with other boundary sets");
    }
    Ok(Converted { mesh, msh })
}

fn from_piece(piece: vtkio::model::UnstructuredGridPiece, dim: usize, opts: &VtkOptions) -> Result<VtkMesh> {
    let n_points = piece.points.len() / 3;
    let coords = buffer_f64(&piece.points).context("points: the coordinates are not numbers")?;
    if coords.len() != 3 * n_points {
        bail!("points: {} coordinates are not x, y, z triples", coords.len());
    }
    if let Some(i) = coords.iter().position(|v| !v.is_finite()) {
        bail!("points: point {} has a coordinate that is not finite", i / 3);
    }
    let cells = cell_lists(&piece.cells.cell_verts, piece.cells.types.len())?;
    let types = &piece.cells.types;
    // Labels: the named array, else the first default one present (a legacy FIELD's arrays by
    // their own names).
    let arrays = cell_arrays(&piece.data.cell);
    let names: Vec<&str> = arrays.iter().map(|a| a.0).collect();
    let array_name = match &opts.label_array {
        Some(n) => {
            if !names.contains(&n.as_str()) {
                bail!("the cell-data array '{}' is not in the file (cell-data arrays: {})", limit::quote(n), list_or_none(&names));
            }
            n.clone()
        }
        None => match DEFAULT_LABEL_ARRAYS.iter().find(|d| names.contains(d)) {
            Some(n) => (*n).to_owned(),
            None => bail!(
                "no label array: the file has no cell-data array named {} (cell-data arrays: {}); name it with the label-array key",
                DEFAULT_LABEL_ARRAYS.join(", "),
                list_or_none(&names)
            ),
        },
    };
    let attr = arrays.iter().find(|a| a.0 == array_name).expect("found above");
    let labels =
        label_values(attr.1, attr.2, types.len()).with_context(|| format!("the cell-data array '{}'", limit::quote(&array_name)))?;

    // Which cells are elements and which boundary cells.
    let (element_type, boundary_type) = if dim == 3 { (CellType::Tetra, CellType::Triangle) } else { (CellType::Triangle, CellType::Line) };
    let mut counts: BTreeMap<u8, usize> = BTreeMap::new();
    for t in types {
        *counts.entry(*t as u8).or_default() += 1;
    }
    if let Some((&t, &n)) = counts.iter().find(|(t, _)| **t != element_type as u8 && **t != boundary_type as u8) {
        let what = if dim == 3 {
            "a 3D mesh holds linear tetrahedra (VTK type 10) and, as boundary faces, triangles (type 5)"
        } else {
            "a 2D mesh holds linear triangles (VTK type 5) and, as boundary edges, lines (type 3)"
        };
        bail!("unsupported cell type: {n} cells of VTK type {t} ({}); {what}", cell_type_name(t));
    }
    if !counts.contains_key(&(element_type as u8)) {
        let found = if dim == 2 && counts.contains_key(&(CellType::Tetra as u8)) { " (tetrahedra make a 3D scene: dim = 3)" } else { "" };
        bail!("the file has no {} to make a {dim}D mesh{found}", if dim == 3 { "tetrahedra" } else { "triangles" });
    }

    // Every label named, every name used.
    let mut label_counts: BTreeMap<i64, (usize, usize)> = BTreeMap::new();
    for (t, &l) in types.iter().zip(&labels) {
        let c = label_counts.entry(l).or_default();
        if *t == element_type { c.0 += 1 } else { c.1 += 1 }
    }
    let describe = |l: i64| {
        let (e, b) = label_counts[&l];
        let (en, bn) = if dim == 3 { ("tetrahedra", "triangles") } else { ("triangles", "lines") };
        match (e, b) {
            (e, 0) => format!("{e} {en}"),
            (0, b) => format!("{b} boundary {bn}"),
            (e, b) => format!("{e} {en} and {b} boundary {bn}"),
        }
    };
    if opts.labels.0.is_empty() {
        let found: Vec<String> = label_counts.keys().map(|&l| format!("{l} ({})", describe(l))).collect();
        bail!(
            "labels missing: name the file's labels (e.g. labels = {{ 1 = \"tissue\" }}, --labels 1=tissue); its labels are {}",
            found.join(", ")
        );
    }
    if let Some(&l) = label_counts.keys().find(|l| !opts.labels.0.contains_key(l)) {
        bail!(
            "unknown label: {} cells are labelled {l} ({}), which the labels map ({}) does not name",
            label_counts[&l].0 + label_counts[&l].1,
            describe(l),
            opts.labels.list()
        );
    }
    if let Some((l, name)) = opts.labels.0.iter().find(|(l, _)| !label_counts.contains_key(l)) {
        let found: Vec<String> = label_counts.keys().map(|l| l.to_string()).collect();
        bail!("empty region: label {l} ('{name}') of the labels map is on no cell of the file (its labels: {})", found.join(", "));
    }

    // Keep nodes used by elements, in file order.
    let mut used = vec![false; n_points];
    for (c, t) in cells.iter().zip(types) {
        for &v in c {
            if v >= n_points {
                bail!("a cell uses point {v}, but the file has {n_points} points");
            }
            if *t == element_type {
                used[v] = true;
            }
        }
    }
    let mut new_index = vec![usize::MAX; n_points];
    let mut nodes_m = Vec::new();
    for (i, _) in used.iter().enumerate().filter(|(_, u)| **u) {
        new_index[i] = nodes_m.len();
        nodes_m.push([coords[3 * i], coords[3 * i + 1], coords[3 * i + 2]]);
    }
    if dim == 2
        && let Some(p) = nodes_m.iter().find(|p| p[2] != nodes_m[0][2])
    {
        bail!("a 2D mesh lies in a plane z = const: points have z = {} and {}", nodes_m[0][2], p[2]);
    }
    let region_labels: Vec<i64> = label_counts.iter().filter(|(_, c)| c.0 > 0).map(|(&l, _)| l).collect();
    let boundary_labels: Vec<i64> = label_counts.iter().filter(|(_, c)| c.1 > 0).map(|(&l, _)| l).collect();
    let mut elements = Vec::new();
    let mut region_of_element = Vec::new();
    let mut boundary: Vec<(i64, String, Vec<Vec<usize>>)> =
        boundary_labels.iter().map(|&l| (l, opts.labels.0[&l].clone(), Vec::new())).collect();
    for (k, ((c, t), l)) in cells.iter().zip(types).zip(&labels).enumerate() {
        let want = if *t == element_type { dim + 1 } else { dim };
        if c.len() != want {
            bail!("cell {k} (VTK type {}) has {} points; it needs {want}", *t as u8, c.len());
        }
        if *t == element_type {
            let e: Vec<usize> = c.iter().map(|&v| new_index[v]).collect();
            check_element(&nodes_m, &e, elements.len(), k)?;
            elements.push(e);
            region_of_element.push(region_labels.binary_search(l).expect("collected above"));
        } else {
            let b = boundary_labels.binary_search(l).expect("collected above");
            // A boundary cell's nodes not on any element are dropped with them.
            boundary[b].2.push(c.iter().map(|&v| new_index[v]).filter(|&v| v != usize::MAX).collect());
        }
    }
    let regions = region_labels.iter().map(|&l| (l, opts.labels.0[&l].clone())).collect();
    Ok(VtkMesh { dim, nodes_m, elements, region_of_element, regions, boundary, label_array: array_name })
}

/// An inverted or degenerate element, named by its index among the elements and in the file.
fn check_element(nodes_m: &[[f64; 3]], e: &[usize], elem_idx: usize, cell_idx: usize) -> Result<()> {
    if e.iter().enumerate().any(|(i, n)| e[..i].contains(n)) {
        bail!("degenerate element: element {elem_idx} (cell {cell_idx} of the file) repeats a point");
    }
    if e.len() == 4 {
        let p = [nodes_m[e[0]], nodes_m[e[1]], nodes_m[e[2]], nodes_m[e[3]]];
        let v = signed_volume_m3(p[0], p[1], p[2], p[3]);
        let h = longest_edge_m(p);
        let tol = DEGENERATE_VOLUME_TOL * h * h * h;
        if v < -tol {
            bail!(
                "inverted element: tetrahedron {elem_idx} (cell {cell_idx} of the file) has a negative volume ({v:e} m³); VTK's tetrahedra are positively oriented (points 0, 1, 2 counter-clockwise seen from point 3)"
            );
        }
        if v.abs() <= tol {
            bail!("degenerate element: tetrahedron {elem_idx} (cell {cell_idx} of the file) has a volume of {v:e} m³ (flat)");
        }
    } else {
        let [a, b, c] = [nodes_m[e[0]], nodes_m[e[1]], nodes_m[e[2]]];
        let area2 = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        let h2 = [(a, b), (b, c), (c, a)].iter().map(|(p, q)| (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).fold(0.0, f64::max);
        if area2.abs() <= 1e-12 * h2 {
            bail!("degenerate element: triangle {elem_idx} (cell {cell_idx} of the file) has an area of {:e} m² (flat)", 0.5 * area2);
        }
    }
    Ok(())
}

fn list_or_none(names: &[&str]) -> String {
    if names.is_empty() { "none".to_owned() } else { names.iter().map(|n| format!("'{}'", limit::quote(n))).collect::<Vec<_>>().join(", ") }
}

fn cell_type_name(t: u8) -> &'static str {
    match t {
        1 => "vertex",
        2 => "poly-vertex",
        3 => "line",
        4 => "poly-line",
        5 => "triangle",
        6 => "triangle strip",
        7 => "polygon",
        8 => "pixel",
        9 => "quad",
        10 => "tetrahedron",
        11 => "voxel",
        12 => "hexahedron",
        13 => "wedge",
        14 => "pyramid",
        21..=34 => "a quadratic cell",
        _ => "a higher-order or special cell",
    }
}

/// The single unstructured-grid piece of a VTK text, XML or legacy.
fn parse_piece(text: &str) -> Result<vtkio::model::UnstructuredGridPiece> {
    let head = text.trim_start_matches('\u{feff}').trim_start();
    let vtk = if head.starts_with('<') {
        check_xml(head)?;
        guarded(|| vtkio::Vtk::parse_xml(head.as_bytes())).map_err(|e| anyhow::anyhow!("malformed VTK XML: {}", clip(&e)))?
    } else if head.starts_with("# vtk DataFile") {
        let binary = head.lines().nth(2).is_some_and(|l| l.trim().eq_ignore_ascii_case("BINARY"));
        if binary {
            bail!("a binary legacy VTK file is not supported: write it as ASCII (or as .vtu)");
        }
        let text = legacy_field_types(head);
        guarded(|| vtkio::Vtk::parse_legacy_be(text.as_bytes())).map_err(|e| anyhow::anyhow!("malformed legacy VTK file: {}", clip(&e)))?
    } else {
        bail!("not a VTK file: neither XML (<VTKFile …>) nor legacy VTK ('# vtk DataFile Version …')");
    };
    let pieces = match vtk.data {
        DataSet::UnstructuredGrid { pieces, .. } => pieces,
        other => bail!("the dataset is {}; an unstructured grid (.vtu, DATASET UNSTRUCTURED_GRID) is needed", dataset_name(&other)),
    };
    if pieces.len() != 1 {
        bail!("the grid has {} pieces; one is needed", pieces.len());
    }
    match pieces.into_iter().next().expect("one piece") {
        Piece::Inline(p) => Ok(*p),
        _ => bail!("the grid's piece is in another file (a parallel .pvtu); give the piece's .vtu"),
    }
}

/// VTK 5.1's sized type names in a FIELD array's header (`name 1 n vtktypeint64`, as meshio
/// writes them) as the classic names the reader knows (`long`, `int`); the `OFFSETS` and
/// `CONNECTIVITY` headers keep theirs.
fn legacy_field_types(text: &str) -> std::borrow::Cow<'_, str> {
    if !text.contains("vtktypeint") {
        return std::borrow::Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len());
    for line in text.split_inclusive('\n') {
        let t: Vec<&str> = line.split_whitespace().collect();
        let classic = match t.as_slice() {
            [_, c, n, ty] if c.parse::<u32>().is_ok() && n.parse::<u64>().is_ok() => match *ty {
                "vtktypeint64" => Some("long"),
                "vtktypeint32" => Some("int"),
                _ => None,
            },
            _ => None,
        };
        match classic {
            Some(c) => {
                out.push_str(&format!("{} {} {} {c}", t[0], t[1], t[2]));
                out.push('\n');
            }
            None => out.push_str(line),
        }
    }
    std::borrow::Cow::Owned(out)
}

fn dataset_name(d: &DataSet) -> &'static str {
    match d {
        DataSet::ImageData { .. } => "image data",
        DataSet::StructuredGrid { .. } => "a structured grid",
        DataSet::RectilinearGrid { .. } => "a rectilinear grid",
        DataSet::UnstructuredGrid { .. } => "an unstructured grid",
        DataSet::PolyData { .. } => "poly data (a surface)",
        DataSet::Field { .. } => "a field",
    }
}

/// Refuses what the XML reader should not see: compressed or raw-appended data (binary bytes
/// and, for compression, sizes taken from the file's own headers) and deep nesting.
fn check_xml(text: &str) -> Result<()> {
    let header_end = text.find("<UnstructuredGrid").or_else(|| text.find("<PolyData")).unwrap_or(text.len().min(4096));
    let header = &text[..header_end];
    if header.contains("compressor=") && !header.contains("compressor=\"\"") {
        bail!("compressed VTK XML is not supported: write the .vtu uncompressed (meshio: compression=None; VTK: SetCompressorTypeToNone)");
    }
    if text.contains("encoding=\"raw\"") {
        bail!(
            "raw appended data is not supported: write the .vtu with ascii or base64 binary data (VTK: SetDataModeToAscii or EncodeAppendedDataOn)"
        );
    }
    let mut depth = 0usize;
    let bytes = text.as_bytes();
    for (i, &b) in bytes.iter().enumerate() {
        if b != b'<' {
            continue;
        }
        match bytes.get(i + 1) {
            Some(b'/') => depth = depth.saturating_sub(1),
            Some(b'?' | b'!') => {}
            _ => {
                let close = text[i..].find('>').map(|j| i + j);
                let self_closing = close.is_some_and(|j| j > 0 && bytes[j - 1] == b'/');
                if !self_closing {
                    depth += 1;
                    if depth > MAX_XML_DEPTH {
                        bail!("malformed VTK XML: elements nested deeper than {MAX_XML_DEPTH} levels");
                    }
                }
            }
        }
    }
    Ok(())
}

/// Runs the parser, a panic on a malformed input becoming an error.
fn guarded<T>(f: impl FnOnce() -> Result<T, vtkio::Error> + std::panic::UnwindSafe) -> Result<T, String> {
    match std::panic::catch_unwind(f) {
        Ok(r) => r.map_err(|e| e.to_string()),
        Err(_) => Err("the reader failed on an inconsistent file".to_owned()),
    }
}

fn clip(s: &str) -> String {
    limit::quote(s)
}

fn buffer_f64(b: &IOBuffer) -> Option<Vec<f64>> {
    match b {
        IOBuffer::F64(v) => Some(v.clone()),
        IOBuffer::F32(v) => Some(v.iter().map(|&x| f64::from(x)).collect()),
        _ => b.cast_into::<f64>(),
    }
}

/// The cell-data arrays: (name, data, components), a legacy FIELD's arrays each by its name.
fn cell_arrays(attrs: &[Attribute]) -> Vec<(&str, &IOBuffer, u32)> {
    use vtkio::model::ElementType;
    let mut out = Vec::new();
    for a in attrs {
        match a {
            Attribute::DataArray(a) => {
                let comps = match &a.elem {
                    ElementType::Scalars { num_comp, .. } => *num_comp,
                    ElementType::Generic(n) => *n,
                    _ => 3,
                };
                out.push((a.name.as_str(), &a.data, comps));
            }
            Attribute::Field { data_array, .. } => out.extend(data_array.iter().map(|f| (f.name.as_str(), &f.data, f.elem))),
        }
    }
    out
}

/// One integer label per cell; floats are accepted when integral.
fn label_values(data: &IOBuffer, comps: u32, n_cells: usize) -> Result<Vec<i64>> {
    if comps != 1 {
        bail!("has {comps} components per cell; labels need one");
    }
    let values: Vec<i64> = match data {
        IOBuffer::F32(_) | IOBuffer::F64(_) => {
            let f = buffer_f64(data).expect("floats");
            if let Some((k, v)) = f.iter().enumerate().find(|(_, v)| !(v.is_finite() && v.fract() == 0.0 && v.abs() < 1e15)) {
                bail!("holds {v} at cell {k}: labels are integers");
            }
            f.iter().map(|&v| v as i64).collect()
        }
        IOBuffer::Bit(_) => bail!("is a bit array; labels are integers"),
        _ => data.cast_into::<i64>().context("holds integers beyond the range of i64")?,
    };
    if values.len() != n_cells {
        bail!("has {} values for {n_cells} cells", values.len());
    }
    Ok(values)
}

/// Each cell's point indices from either layout of the connectivity.
fn cell_lists(v: &VertexNumbers, n_types: usize) -> Result<Vec<Vec<usize>>> {
    let mut out = Vec::with_capacity(n_types);
    match v {
        VertexNumbers::Legacy { num_cells, vertices } => {
            let mut i = 0;
            for k in 0..*num_cells as usize {
                let n = *vertices.get(i).with_context(|| format!("cells: the connectivity ends before cell {k}"))? as usize;
                let c = vertices.get(i + 1..i + 1 + n).with_context(|| format!("cells: the connectivity ends inside cell {k}"))?;
                out.push(c.iter().map(|&x| x as usize).collect());
                i += 1 + n;
            }
        }
        VertexNumbers::XML { connectivity, offsets } => {
            // Offsets end each cell; a leading 0 (some writers) is skipped.
            let offs: &[u64] = if offsets.len() == n_types + 1 && offsets.first() == Some(&0) { &offsets[1..] } else { offsets };
            let mut start = 0u64;
            for (k, &end) in offs.iter().enumerate() {
                if end < start || end > connectivity.len() as u64 {
                    bail!("cells: offset {end} of cell {k} is out of order or past the connectivity ({} entries)", connectivity.len());
                }
                out.push(connectivity[start as usize..end as usize].iter().map(|&x| x as usize).collect());
                start = end;
            }
        }
    }
    if out.len() != n_types {
        bail!("cells: {} cells but {n_types} cell types", out.len());
    }
    Ok(out)
}

impl VtkMesh {
    /// The boundary sets: the nodes of each set's cells, sorted, without repeats.
    fn boundary_sets(&self) -> BTreeMap<String, Vec<usize>> {
        self.boundary
            .iter()
            .map(|(_, name, cells)| {
                let mut nodes: Vec<usize> = cells.iter().flatten().copied().collect();
                nodes.sort_unstable();
                nodes.dedup();
                (name.clone(), nodes)
            })
            .collect()
    }

    /// The region names, by increasing label.
    pub fn region_names(&self) -> Vec<String> {
        self.regions.iter().map(|(_, n)| n.clone()).collect()
    }

    /// The tetrahedral mesh (3D).
    pub fn to_tet_mesh(&self, limits: &TetMeshLimits) -> Result<TetMesh> {
        if self.dim != 3 {
            bail!("a 2D mesh is not a tetrahedral mesh");
        }
        let tets = self.elements.iter().map(|e| [e[0], e[1], e[2], e[3]]).collect();
        Ok(TetMesh::with_regions(
            self.nodes_m.clone(),
            tets,
            self.region_of_element.clone(),
            self.region_names(),
            self.boundary_sets(),
            limits,
        )?)
    }

    /// The triangle mesh (2D).
    pub fn to_tri_mesh(&self, limits: &MeshLimits) -> Result<Mesh> {
        if self.dim != 2 {
            bail!("a 3D mesh is not a triangle mesh");
        }
        let nodes = self.nodes_m.iter().map(|p| [p[0], p[1]]).collect();
        let tris = self.elements.iter().map(|e| [e[0], e[1], e[2]]).collect();
        Ok(Mesh::with_regions(nodes, tris, self.region_of_element.clone(), self.region_names(), self.boundary_sets(), limits)?)
    }

    /// Each region's measure (volume in 3D, area in 2D), by region.
    pub fn region_measures(&self) -> Vec<f64> {
        let mut m = vec![0.0; self.regions.len()];
        for (e, &r) in self.elements.iter().zip(&self.region_of_element) {
            let p: Vec<[f64; 3]> = e.iter().map(|&i| self.nodes_m[i]).collect();
            m[r] += if self.dim == 3 {
                signed_volume_m3(p[0], p[1], p[2], p[3]).abs()
            } else {
                0.5 * ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0])).abs()
            };
        }
        m
    }
}

/// Writes the mesh as Gmsh MSH 4.1 ASCII: one physical group per region (dimension `dim`) and
/// per boundary set (dimension `dim - 1`), tagged by its label and named; one entity per group;
/// the nodes in one block, tagged 1…n in order; elements tagged 1…, elements first.
pub fn write_msh41(m: &VtkMesh) -> String {
    let d = m.dim;
    let (elem_type, bnd_type) = if d == 3 { (4, 2) } else { (2, 1) };
    let mut s = String::new();
    s.push_str("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n");
    let _ = writeln!(s, "{}", m.regions.len() + m.boundary.len());
    for (l, name, _) in &m.boundary {
        let _ = writeln!(s, "{} {l} \"{name}\"", d - 1);
    }
    for (l, name) in &m.regions {
        let _ = writeln!(s, "{d} {l} \"{name}\"");
    }
    s.push_str("$EndPhysicalNames\n$Entities\n");
    let bbox = |nodes: &mut dyn Iterator<Item = usize>| {
        let mut b = [f64::INFINITY, f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY];
        for i in nodes {
            for k in 0..3 {
                b[k] = b[k].min(m.nodes_m[i][k]);
                b[k + 3] = b[k + 3].max(m.nodes_m[i][k]);
            }
        }
        b.map(|v| if v.is_finite() { v } else { 0.0 }).map(|v| format!("{v:?}")).join(" ")
    };
    let mut counts = [0usize; 4];
    counts[d] = m.regions.len();
    counts[d - 1] = m.boundary.len();
    let _ = writeln!(s, "{} {} {} {}", counts[0], counts[1], counts[2], counts[3]);
    // Entities in increasing dimension: boundary sets, then regions (tags 1…).
    for (k, (l, _, cells)) in m.boundary.iter().enumerate() {
        let _ = writeln!(s, "{} {} 1 {l} 0", k + 1, bbox(&mut cells.iter().flatten().copied()));
    }
    for (k, (l, _)) in m.regions.iter().enumerate() {
        let mut nodes = m.elements.iter().zip(&m.region_of_element).filter(|(_, r)| **r == k).flat_map(|(e, _)| e.iter().copied());
        let _ = writeln!(s, "{} {} 1 {l} 0", k + 1, bbox(&mut nodes));
    }
    s.push_str("$EndEntities\n$Nodes\n");
    let n = m.nodes_m.len();
    let _ = writeln!(s, "1 {n} 1 {n}\n{d} 1 0 {n}");
    for i in 1..=n {
        let _ = writeln!(s, "{i}");
    }
    for p in &m.nodes_m {
        let _ = writeln!(s, "{:?} {:?} {:?}", p[0], p[1], p[2]);
    }
    s.push_str("$EndNodes\n$Elements\n");
    let n_bnd: usize = m.boundary.iter().map(|b| b.2.iter().filter(|c| c.len() == d).count()).sum();
    let n_el = m.elements.len() + n_bnd;
    let _ = writeln!(s, "{} {n_el} 1 {n_el}", m.regions.len() + m.boundary.len());
    let mut tag = 1;
    for k in 0..m.regions.len() {
        let mine: Vec<&Vec<usize>> = m.elements.iter().zip(&m.region_of_element).filter(|(_, r)| **r == k).map(|(e, _)| e).collect();
        let _ = writeln!(s, "{d} {} {elem_type} {}", k + 1, mine.len());
        for e in mine {
            let _ = write!(s, "{tag}");
            for v in e {
                let _ = write!(s, " {}", v + 1);
            }
            s.push('\n');
            tag += 1;
        }
    }
    for (k, (_, _, cells)) in m.boundary.iter().enumerate() {
        let whole: Vec<&Vec<usize>> = cells.iter().filter(|c| c.len() == d).collect();
        let _ = writeln!(s, "{} {} {bnd_type} {}", d - 1, k + 1, whole.len());
        for c in whole {
            let _ = write!(s, "{tag}");
            for v in c {
                let _ = write!(s, " {}", v + 1);
            }
            s.push('\n');
            tag += 1;
        }
    }
    s.push_str("$EndElements\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit cube of 5 tetrahedra (the middle one labelled 2, the corners 1) and its bottom face's
    /// two triangles labelled 11, as ASCII VTU; `cells` replaces the cell list when given.
    fn cube_vtu(labels_name: &str, extra_cells: &[(u8, &[usize], i64)]) -> String {
        let pts = [[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [1., 1., 0.], [0., 0., 1.], [1., 0., 1.], [0., 1., 1.], [1., 1., 1.]];
        let mut cells: Vec<(u8, Vec<usize>, i64)> = vec![
            (10, vec![0, 1, 2, 4], 1),
            (10, vec![1, 3, 2, 7], 1),
            (10, vec![1, 4, 5, 7], 1),
            (10, vec![2, 7, 6, 4], 1),
            (10, vec![1, 2, 4, 7], 2),
            (5, vec![0, 2, 1], 11),
            (5, vec![1, 2, 3], 11),
        ];
        cells.extend(extra_cells.iter().map(|(t, c, l)| (*t, c.to_vec(), *l)));
        let mut conn = String::new();
        let mut offs = String::new();
        let mut off = 0;
        for (_, c, _) in &cells {
            off += c.len();
            conn += &c.iter().map(|v| v.to_string()).collect::<Vec<_>>().join(" ");
            conn.push(' ');
            offs += &format!("{off} ");
        }
        let types: Vec<String> = cells.iter().map(|c| c.0.to_string()).collect();
        let labels: Vec<String> = cells.iter().map(|c| c.2.to_string()).collect();
        let points: Vec<String> = pts.iter().map(|p| format!("{} {} {}", p[0], p[1], p[2])).collect();
        format!(
            r#"<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">
  <UnstructuredGrid>
    <Piece NumberOfPoints="{}" NumberOfCells="{}">
      <Points>
        <DataArray type="Float64" NumberOfComponents="3" format="ascii">{}</DataArray>
      </Points>
      <Cells>
        <DataArray type="Int64" Name="connectivity" format="ascii">{conn}</DataArray>
        <DataArray type="Int64" Name="offsets" format="ascii">{offs}</DataArray>
        <DataArray type="UInt8" Name="types" format="ascii">{}</DataArray>
      </Cells>
      <CellData>
        <DataArray type="Int32" Name="{labels_name}" format="ascii">{}</DataArray>
      </CellData>
    </Piece>
  </UnstructuredGrid>
</VTKFile>
"#,
            pts.len(),
            cells.len(),
            points.join(" "),
            types.join(" "),
            labels.join(" ")
        )
    }

    fn opts(list: &str) -> VtkOptions {
        VtkOptions { labels: LabelMap::parse_list(list).unwrap(), label_array: None }
    }

    const LABELS: &str = "1=tissue,2=lesion,11=bottom";

    fn err(text: &str, dim: usize, o: &VtkOptions) -> String {
        format!("{:#}", read_vtk(text, dim, o).expect_err("refused"))
    }

    #[test]
    fn a_labelled_vtu_reads_to_regions_volumes_and_boundary_sets() {
        let m = read_vtk(&cube_vtu("CellEntityIds", &[]), 3, &opts(LABELS)).unwrap();
        assert_eq!((m.dim, m.nodes_m.len(), m.elements.len(), m.label_array.as_str()), (3, 8, 5, "CellEntityIds"));
        assert_eq!(m.region_names(), ["tissue", "lesion"]);
        let v = m.region_measures();
        assert!((v[1] - 1.0 / 3.0).abs() < 1e-15 && (v[0] - 2.0 / 3.0).abs() < 1e-15, "{v:?}");
        let t = m.to_tet_mesh(&TetMeshLimits::default()).unwrap();
        assert_eq!(t.boundary_set("bottom").unwrap(), &[0, 1, 2, 3]);
        assert_eq!(t.region_of_tet(), &[0, 0, 0, 0, 1]);
    }

    #[test]
    fn the_msh_written_reads_back_to_the_same_regions_volumes_and_sets() {
        let c = convert_to_msh("cube.vtu", &cube_vtu("labels", &[]), &opts(LABELS)).unwrap();
        let back = needlesim_core::msh::parse_msh3d(&c.msh, &TetMeshLimits::default()).unwrap();
        assert_eq!(back.version, "4.1");
        assert_eq!(back.mesh.region_names(), ["tissue", "lesion"]);
        assert_eq!(back.mesh.boundary_set("bottom").unwrap(), &[0, 1, 2, 3]);
        assert_eq!(back.mesh.nodes_m(), c.mesh.nodes_m.as_slice());
        assert!(c.msh.contains("$PhysicalNames\n3\n2 11 \"bottom\"\n3 1 \"tissue\"\n3 2 \"lesion\"\n"), "{}", c.msh);
    }

    #[test]
    fn a_2d_triangle_vtu_and_a_legacy_vtk_read() {
        // Two triangles of a unit square, labels 1 and 2, the bottom edge a line labelled 5.
        let legacy = "# vtk DataFile Version 4.2\nsquare\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n0 0 0 1 0 0 1 1 0 0 1 0\n\
                      CELLS 3 11\n3 0 1 2\n3 0 2 3\n2 0 1\nCELL_TYPES 3\n5\n5\n3\nCELL_DATA 3\nSCALARS region int 1\nLOOKUP_TABLE default\n1\n2\n5\n";
        let o = opts("1=left,2=right,5=bottom");
        let m = read_vtk(legacy, 2, &o).unwrap();
        assert_eq!(m.region_names(), ["left", "right"]);
        assert_eq!(m.region_measures(), [0.5, 0.5]);
        let mesh = m.to_tri_mesh(&MeshLimits::default()).unwrap();
        assert_eq!(mesh.boundary_set("bottom").unwrap(), &[0, 1]);
        let c = convert_to_msh("square.vtk", legacy, &o).unwrap();
        let back = needlesim_core::msh::parse_msh(&c.msh, &MeshLimits::default()).unwrap().mesh;
        assert_eq!(back.region_names(), ["left", "right"]);
        assert_eq!(back.boundary_set("bottom").unwrap(), &[0, 1]);
        // VTK 5.1 as meshio writes it: OFFSETS and CONNECTIVITY, the labels in a FIELD.
        let v51 = "# vtk DataFile Version 5.1\nsquare\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n0 0 0 1 0 0 1 1 0 0 1 0\n\
                   CELLS 4 8\nOFFSETS vtktypeint64\n0 3 6 8\nCONNECTIVITY vtktypeint64\n0 1 2 0 2 3 0 1\nCELL_TYPES 3\n5\n5\n3\n\
                   CELL_DATA 3\nFIELD FieldData 1\ngmsh:physical 1 3 vtktypeint64\n1 2 5\n";
        let m51 = read_vtk(v51, 2, &o).unwrap();
        assert_eq!((m51.region_names(), m51.label_array.as_str()), (vec!["left".to_owned(), "right".to_owned()], "gmsh:physical"));
        assert_eq!(m51.elements, m.elements);
        // A 2D mesh must be planar.
        let tilted = legacy.replace("0 0 0 1 0 0 1 1 0 0 1 0", "0 0 0 1 0 0 1 1 0.5 0 1 0");
        assert!(err(&tilted, 2, &o).contains("a 2D mesh lies in a plane z = const"));
    }

    #[test]
    fn bad_input_is_refused_naming_the_problem() {
        let o = opts(LABELS);
        let good = cube_vtu("labels", &[]);
        // A label of the file not in the map, a label of the map on no cell, no map.
        let e = err(&good, 3, &opts("1=tissue,2=lesion"));
        assert!(
            e.contains(
                "unknown label: 2 cells are labelled 11 (2 boundary triangles), which the labels map (1=tissue,2=lesion) does not name"
            ),
            "{e}"
        );
        let e = err(&good, 3, &opts("1=tissue,2=lesion,3=vessel,11=bottom"));
        assert!(e.contains("empty region: label 3 ('vessel') of the labels map is on no cell of the file (its labels: 1, 2, 11)"), "{e}");
        let e = err(&good, 3, &VtkOptions::default());
        assert!(e.contains("labels missing") && e.contains("1 (4 tetrahedra), 2 (1 tetrahedra), 11 (2 boundary triangles)"), "{e}");
        // Bad maps.
        assert!(format!("{:#}", LabelMap::parse_list("1=a,2=a").unwrap_err()).contains("labels 1 and 2 are both named 'a'"));
        assert!(format!("{:#}", LabelMap::parse_list("x=a").unwrap_err()).contains("'x' is not an integer label"));
        assert!(format!("{:#}", LabelMap::parse_list("1").unwrap_err()).contains("'1' is not LABEL=NAME"));
        // No label array; a named one that is absent.
        let e = err(&cube_vtu("density", &[]), 3, &o);
        assert!(e.contains("no label array") && e.contains("'density'"), "{e}");
        let e = err(&good, 3, &VtkOptions { label_array: Some("tags".into()), ..o.clone() });
        assert!(e.contains("the cell-data array 'tags' is not in the file (cell-data arrays: 'labels')"), "{e}");
        // An inverted and a degenerate tetrahedron.
        let inverted = cube_vtu("labels", &[]).replace("1 2 4 7 ", "2 1 4 7 ");
        let e = err(&inverted, 3, &o);
        assert!(e.contains("inverted element: tetrahedron 4 (cell 4 of the file) has a negative volume"), "{e}");
        let flat = cube_vtu("labels", &[(10, &[0, 1, 3, 2], 1)]);
        let e = err(&flat, 3, &o);
        assert!(e.contains("degenerate element: tetrahedron 5 (cell 7 of the file)"), "{e}");
        // Other cell types; tetrahedra in a 2D scene.
        let hex = cube_vtu("labels", &[(12, &[0, 1, 3, 2, 4, 5, 7, 6], 1)]);
        let e = err(&hex, 3, &o);
        assert!(e.contains("unsupported cell type: 1 cells of VTK type 12 (hexahedron)"), "{e}");
        let e = err(&good, 2, &o);
        assert!(e.contains("unsupported cell type: 5 cells of VTK type 10 (tetrahedron)"), "{e}");
        // Malformed XML, compressed or raw data, a binary legacy file, neither format.
        let e = err(&good.replace("</Points>", ""), 3, &o);
        assert!(e.starts_with("malformed VTK XML"), "{e}");
        let e = err(&good.replace("<Piece NumberOfPoints=\"8\"", "<Piece NumberOfPoints=\"9\""), 3, &o);
        assert!(e.contains("malformed") || e.contains("points"), "{e}");
        let e =
            err(&good.replace("byte_order=\"LittleEndian\"", "byte_order=\"LittleEndian\" compressor=\"vtkZLibDataCompressor\""), 3, &o);
        assert!(e.contains("compressed VTK XML is not supported"), "{e}");
        let e = err(&good.replace("<Piece", "<AppendedData encoding=\"raw\"/><Piece"), 3, &o);
        assert!(e.contains("raw appended data is not supported"), "{e}");
        let deep = good.replace("<Points>", &format!("<Points>{}", "<a>".repeat(40)));
        assert!(err(&deep, 3, &o).contains("nested deeper than 32"));
        let e = err("# vtk DataFile Version 3.0\nx\nBINARY\nDATASET UNSTRUCTURED_GRID\n", 3, &o);
        assert!(e.contains("binary legacy VTK file is not supported"), "{e}");
        assert!(err("solid cube\n", 3, &o).starts_with("not a VTK file"));
        // The mesh command's inputs.
        let e = format!("{:#}", convert_to_msh("head.nii.gz", "", &o).err().unwrap());
        assert!(e.contains("labelmaps (NIfTI, NRRD) are not yet supported"), "{e}");
        let e = format!("{:#}", convert_to_msh("head.stl", "", &o).err().unwrap());
        assert!(e.contains("must be a VTK mesh (.vtu, .vtk) or a labelmap"), "{e}");
    }

    /// 3D scenes on a VTU: regions and fixed sets from the labels, materials from the library
    /// with written keys overriding; over the API the file comes uploaded or is refused unread.
    #[test]
    fn scenes_on_a_vtu_take_labels_materials_and_the_file_rule() {
        use crate::{SceneFiles, SceneLimits, parse_scene3d_with};
        let limits = SceneLimits::from(&MeshLimits::default());
        let vtu = cube_vtu("labels", &[]);
        let toml = |labels: &str, lesion: &str| {
            format!(
                "dim = 3\nfixed = [\"bottom\"]\n[mesh]\ntype = \"vtu\"\nfile = \"cube.vtu\"\nlabels = {{ {labels} }}\n\n\
                 [[regions]]\nname = \"tissue\"\nmaterial = \"liver\"\n\n[[regions]]\nname = \"lesion\"\n{lesion}\n\n\
                 [needle]\nlength_m = 0.1\nbase_m = [0.5, 0.5, 1.2]\nbase_axis = [0.0, 0.0, -1.0]\n"
            )
        };
        let labels = "1 = \"tissue\", 2 = \"lesion\", 11 = \"bottom\"";
        let given = [("cube.vtu", vtu.as_str())];
        let s = parse_scene3d_with(&toml(labels, "material = \"prostate\"\nyoung_modulus_pa = 90e3"), SceneFiles::Given(&given), limits)
            .unwrap();
        let liver = crate::tissues::tissue("liver").unwrap();
        assert_eq!(s.regions[0].material.young_modulus_pa, liver.young_modulus_pa);
        assert_eq!(s.regions[0].needle.cutting_force_n, liver.cutting_force_n.unwrap());
        assert_eq!(s.regions[1].material.young_modulus_pa, 90e3, "the written key overrides the material");
        assert_eq!(s.regions[1].needle.puncture_force_n, crate::tissues::tissue("prostate").unwrap().puncture_force_n.unwrap());
        assert_eq!(s.fixed_nodes, [0, 1, 2, 3]);
        assert_eq!(s.mesh_source, crate::scene3d::MeshSource3d::Vtu { file: "cube.vtu".into(), label_array: "labels".into() });
        // An unknown material, a region without values, a label the scene lacks.
        let e = format!("{:#}", parse_scene3d_with(&toml(labels, "material = \"livr\""), SceneFiles::Given(&given), limits).unwrap_err());
        assert!(e.contains("material = \"livr\" is not in the tissue library"), "{e}");
        let e = format!("{:#}", parse_scene3d_with(&toml(labels, "poisson_ratio = 0.4"), SceneFiles::Given(&given), limits).unwrap_err());
        assert!(e.contains("region 'lesion': young_modulus_pa is missing"), "{e}");
        let e = format!(
            "{:#}",
            parse_scene3d_with(&toml("1 = \"tissue\", 2 = \"lesion\"", "material = \"fat\""), SceneFiles::Given(&given), limits)
                .unwrap_err()
        );
        assert!(e.contains("mesh.file = \"cube.vtu\"") && e.contains("unknown label"), "{e}");
        // From a client: nothing is opened.
        let e = format!("{:#}", parse_scene3d_with(&toml(labels, "material = \"fat\""), SceneFiles::None, limits).unwrap_err());
        assert!(e.contains("mesh.file = \"cube.vtu\": a scene sent to the server cannot name files"), "{e}");
    }

    /// A 2D scene on a triangle VTU with materials (the toughness of the library's material
    /// applies with energy-based cutting only).
    #[test]
    fn a_2d_scene_on_a_vtu_with_materials() {
        use crate::{SceneFiles, parse_scene_with};
        let vtk = "# vtk DataFile Version 4.2\nsquare\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n0 0 0 0.1 0 0 0.1 0.1 0 0 0.1 0\n\
                   CELLS 3 11\n3 0 1 2\n3 0 2 3\n2 0 1\nCELL_TYPES 3\n5\n5\n3\nCELL_DATA 3\nSCALARS region int 1\nLOOKUP_TABLE default\n1\n1\n5\n";
        let given = [("square.vtk", vtk)];
        let scene = |cutting: &str| {
            format!(
                "fixed = [\"bottom\"]\n[mesh]\ntype = \"vtk\"\nfile = \"square.vtk\"\nlabels = {{ 1 = \"gel\", 5 = \"bottom\" }}\n\n\
                 [[regions]]\nname = \"gel\"\nmaterial = \"gelatine_phantom\"\n\n[needle]\nlength_m = 0.1\nbase = [0.05, 0.205, -1.5707963267948966]\n{cutting}"
            )
        };
        let s = parse_scene_with(&scene(""), SceneFiles::Given(&given), &MeshLimits::default()).unwrap();
        let gel = crate::tissues::tissue("gelatine_phantom").unwrap();
        assert_eq!(s.params.regions[0].friction_n_per_m, gel.friction_n_per_m.unwrap());
        assert_eq!(s.params.regions[0].toughness_cutting_force_n, None);
        assert_eq!(s.tissue.mesh().n_triangles(), 2);
        let s =
            parse_scene_with(&scene("cutting = \"toughness\"\ndiameter_m = 0.001\n"), SceneFiles::Given(&given), &MeshLimits::default())
                .unwrap();
        let fc = s.params.regions[0].toughness_cutting_force_n.unwrap();
        assert!((fc - gel.fracture_toughness_j_per_m2.unwrap() * 0.001).abs() < 1e-15, "{fc}");
    }

    /// Every truncation of a valid file is refused with an error, never a panic.
    #[test]
    fn truncated_files_are_errors() {
        let good = cube_vtu("labels", &[]);
        for cut in (0..good.len()).step_by(7) {
            if good.is_char_boundary(cut) {
                assert!(read_vtk(&good[..cut], 3, &opts(LABELS)).is_err(), "cut at {cut}");
            }
        }
    }
}
