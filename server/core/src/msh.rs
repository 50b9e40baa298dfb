//! Import of Gmsh ASCII meshes, MSH 2.2 and 4.1, from text (the caller reads the file).
//!
//! Linear triangles (element type 2) become the mesh; their 2D physical group is the region
//! (named from `$PhysicalNames`, else `physical<tag>`; triangles of no group form the region
//! `default`). Lines (type 1) and points (type 15) in physical groups become named boundary node
//! sets, e.g. a fixed edge. Nodes keep the order of `$Nodes`; nodes used by no triangle (geometry
//! points such as a circle's centre) are dropped, and [`MshMesh::node_tags`] maps each mesh node
//! back to its Gmsh tag. Other 2D element types (quadrangles, quadratic triangles) are rejected.
//! Every error names the line where it was found. A hand-written parser: the crates we looked at
//! read only MSH 4.1 and report no line numbers.

use std::collections::{BTreeMap, HashMap};

use crate::d3::mesh::{TetMesh, TetMeshError, TetMeshLimits, longest_edge_m, signed_volume_m3};
use crate::mesh::{Mesh, MeshError, MeshLimits};

impl From<MeshError> for MshError {
    fn from(e: MeshError) -> Self {
        MshError::Mesh(e)
    }
}

impl From<TetMeshError> for MshError {
    fn from(e: TetMeshError) -> Self {
        MshError::TetMesh(e)
    }
}

/// An error in an MSH file, with the 1-based line where it was found.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MshError {
    /// The text is not a valid MSH file.
    #[error("MSH line {line}: {message}")]
    Syntax { line: usize, message: String },
    /// The file parsed, but the mesh it describes is invalid. Its words are in the message, and
    /// it is not also the error's source: a chain printed whole (`{:#}`) says them once.
    #[error("MSH mesh: {0}")]
    Mesh(MeshError),
    /// The file parsed, but the tetrahedral mesh it describes is invalid (said once, as
    /// [`MshError::Mesh`]).
    #[error("MSH mesh: {0}")]
    TetMesh(TetMeshError),
    /// A tetrahedron is invalid (degenerate, repeated, a node twice, or inverted: negative volume),
    /// named by its line and Gmsh element tag.
    #[error("MSH line {line}: tetrahedron with element tag {tag}: {message}")]
    Tetrahedron { line: usize, tag: u64, message: String },
}

/// A tetrahedral mesh read from an MSH file by [`parse_msh3d`].
#[derive(Debug, Clone, PartialEq)]
pub struct MshTetMesh {
    /// The mesh, with regions (physical volumes) and boundary sets (physical surfaces, curves, points).
    pub mesh: TetMesh,
    /// The Gmsh node tag of each mesh node.
    pub node_tags: Vec<u64>,
    /// The Gmsh element tag of each tetrahedron.
    pub element_tags: Vec<u64>,
    /// The format version read (`2.2` or `4.1`).
    pub version: String,
}

/// A mesh read from an MSH file.
#[derive(Debug, Clone, PartialEq)]
pub struct MshMesh {
    /// The mesh, with regions and boundary sets.
    pub mesh: Mesh,
    /// The Gmsh node tag of each mesh node.
    pub node_tags: Vec<u64>,
    /// The format version read (`2.2` or `4.1`).
    pub version: String,
}

struct Cursor<'a> {
    lines: Vec<(usize, &'a str)>,
    pos: usize,
    tokens: std::vec::IntoIter<&'a str>,
    line: usize,
}

fn syntax(line: usize, message: impl Into<String>) -> MshError {
    MshError::Syntax { line, message: message.into() }
}

impl<'a> Cursor<'a> {
    fn new(text: &'a str) -> Self {
        let lines = text.lines().enumerate().map(|(i, l)| (i + 1, l.trim())).filter(|(_, l)| !l.is_empty()).collect();
        Self { lines, pos: 0, tokens: Vec::new().into_iter(), line: 0 }
    }
    /// The next whole line (discarding the rest of the current one).
    fn next_line(&mut self) -> Option<(usize, &'a str)> {
        self.tokens = Vec::new().into_iter();
        let l = self.lines.get(self.pos).copied();
        if let Some((n, _)) = l {
            self.pos += 1;
            self.line = n;
        }
        l
    }
    fn last_line(&self) -> usize {
        self.lines.last().map_or(1, |l| l.0)
    }
    /// Starts reading tokens from the next line.
    fn begin_line(&mut self, what: &str) -> Result<(), MshError> {
        let (_, l) = self.next_line().ok_or_else(|| syntax(self.last_line(), format!("unexpected end of file, expected {what}")))?;
        self.tokens = split_tokens(l).into_iter();
        Ok(())
    }
    fn token(&mut self, what: &str) -> Result<&'a str, MshError> {
        self.tokens.next().ok_or_else(|| syntax(self.line, format!("missing {what}")))
    }
    fn usize(&mut self, what: &str) -> Result<usize, MshError> {
        let t = self.token(what)?;
        t.parse().map_err(|_| syntax(self.line, format!("{what} must be a non-negative integer, found '{}'", truncate(t))))
    }
    fn i64(&mut self, what: &str) -> Result<i64, MshError> {
        let t = self.token(what)?;
        t.parse().map_err(|_| syntax(self.line, format!("{what} must be an integer, found '{}'", truncate(t))))
    }
    fn f64(&mut self, what: &str) -> Result<f64, MshError> {
        let t = self.token(what)?;
        let v: f64 = t.parse().map_err(|_| syntax(self.line, format!("{what} must be a number, found '{}'", truncate(t))))?;
        if !v.is_finite() {
            return Err(syntax(self.line, format!("{what} is not finite: '{}'", truncate(t))));
        }
        Ok(v)
    }
    fn end_of_line(&mut self) -> Result<(), MshError> {
        match self.tokens.next() {
            None => Ok(()),
            Some(t) => Err(syntax(self.line, format!("unexpected '{}' at the end of the line", truncate(t)))),
        }
    }
    fn expect_line(&mut self, marker: &str) -> Result<(), MshError> {
        match self.next_line() {
            Some((_, l)) if l == marker => Ok(()),
            Some((n, l)) => Err(syntax(n, format!("expected {marker}, found '{}'", truncate(l)))),
            None => Err(syntax(self.last_line(), format!("unexpected end of file, expected {marker}"))),
        }
    }
    /// Skips to the line after `marker`.
    fn skip_section(&mut self, marker: &str, start_line: usize) -> Result<(), MshError> {
        while let Some((_, l)) = self.next_line() {
            if l == marker {
                return Ok(());
            }
        }
        Err(syntax(start_line, format!("section is not closed by {marker}")))
    }
}

fn truncate(s: &str) -> String {
    if s.chars().count() > 40 { format!("{}…", s.chars().take(40).collect::<String>()) } else { s.to_owned() }
}

/// Splits on whitespace, keeping a double-quoted name as one token.
fn split_tokens(l: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let mut rest = l.trim_start();
    while !rest.is_empty() {
        if let Some(stripped) = rest.strip_prefix('"') {
            let end = stripped.find('"').map_or(rest.len(), |e| e + 2);
            out.push(&rest[..end]);
            rest = rest[end..].trim_start();
        } else {
            let end = rest.find(char::is_whitespace).unwrap_or(rest.len());
            out.push(&rest[..end]);
            rest = rest[end..].trim_start();
        }
    }
    out
}

#[derive(Default)]
struct Raw {
    names: HashMap<(usize, i64), String>,
    nodes: Vec<(u64, [f64; 3])>,
    /// (gmsh node tags, physical tag or None, line)
    triangles: Vec<([u64; 3], Option<i64>, usize)>,
    /// 3D only: (gmsh node tags, physical tag or None, element tag, line)
    tets: Vec<([u64; 4], Option<i64>, u64, usize)>,
    /// (dim, physical tag, node tags)
    groups: Vec<(usize, i64, Vec<u64>)>,
}

/// Parses MSH 2.2 or 4.1 ASCII text into a validated mesh.
pub fn parse_msh(text: &str, limits: &MeshLimits) -> Result<MshMesh, MshError> {
    let (raw, version) = read_raw(text, limits.max_nodes, limits.max_triangles.saturating_mul(4), false)
        .map_err(|e| e.into_mesh_error(limits.max_triangles))?;
    build(raw, version, limits)
}

/// Parses MSH 2.2 or 4.1 ASCII text with linear tetrahedra (element type 4) into a validated
/// [`TetMesh`]. Physical volumes are regions (named from `$PhysicalNames`, else `physical<tag>`;
/// tetrahedra of no group form `default`; regions in increasing tag order); triangles (type 2),
/// lines (1) and points (15) in physical groups become named boundary node sets. The nodes that
/// tetrahedra use are kept in file order and renumbered from 0 ([`MshTetMesh::node_tags`] maps
/// back). Other 3D element types (hexahedra, prisms, pyramids, quadratic tetrahedra) and
/// quadrangles are rejected. Gmsh writes positively oriented tetrahedra: a tetrahedron of
/// negative volume is rejected as inverted (not reoriented), naming its line and tag; so are a
/// degenerate or repeated one. Every error names its line.
pub fn parse_msh3d(text: &str, limits: &TetMeshLimits) -> Result<MshTetMesh, MshError> {
    let (raw, version) =
        read_raw(text, limits.max_nodes, limits.max_tets.saturating_mul(4), true).map_err(|e| e.into_tet_error(limits.max_tets))?;
    build3d(raw, version, limits)
}

/// An element-count overflow found while reading, reported as the caller's mesh error.
enum ReadError {
    Msh(MshError),
    TooManyNodes { n_nodes: usize, max_nodes: usize },
    TooManyElements { n_elements: usize },
}

impl From<MshError> for ReadError {
    fn from(e: MshError) -> Self {
        ReadError::Msh(e)
    }
}

impl ReadError {
    fn into_mesh_error(self, max_triangles: usize) -> MshError {
        match self {
            ReadError::Msh(e) => e,
            ReadError::TooManyNodes { n_nodes, max_nodes } => MeshError::TooManyNodes { n_nodes, max_nodes }.into(),
            ReadError::TooManyElements { n_elements } => MeshError::TooManyTriangles { n_triangles: n_elements, max_triangles }.into(),
        }
    }
    fn into_tet_error(self, max_tets: usize) -> MshError {
        match self {
            ReadError::Msh(e) => e,
            ReadError::TooManyNodes { n_nodes, max_nodes } => TetMeshError::TooManyNodes { n_nodes, max_nodes }.into(),
            ReadError::TooManyElements { n_elements } => TetMeshError::TooManyTets { n_tets: n_elements, max_tets }.into(),
        }
    }
}

/// The limits and mode of one read.
#[derive(Clone, Copy)]
struct ReadLimits {
    max_nodes: usize,
    max_elements: usize,
    three_d: bool,
}

fn read_raw(text: &str, max_nodes: usize, max_elements: usize, three_d: bool) -> Result<(Raw, String), ReadError> {
    let lim = ReadLimits { max_nodes, max_elements, three_d };
    let limits = &lim;
    let mut c = Cursor::new(text);
    c.expect_line("$MeshFormat")?;
    c.begin_line("the format line")?;
    let version = c.token("version")?.to_owned();
    let file_type = c.usize("file type")?;
    let _data_size = c.usize("data size")?;
    let format_line = c.line;
    if file_type != 0 {
        return Err(syntax(format_line, "binary MSH files are not supported; save as ASCII").into());
    }
    let v4 = match version.as_str() {
        "2.2" | "2.1" | "2" | "2.0" => false,
        "4.1" => true,
        v => return Err(syntax(format_line, format!("MSH version {v} is not supported; use 2.2 or 4.1")).into()),
    };
    c.expect_line("$EndMeshFormat")?;
    let mut raw = Raw::default();
    // entity (dim, tag) -> physical tags (4.1)
    let mut entity_phys: HashMap<(usize, i64), Vec<i64>> = HashMap::new();
    let (mut seen_nodes, mut seen_elements) = (false, false);
    while let Some((line, l)) = c.next_line() {
        match l {
            "$PhysicalNames" => {
                c.begin_line("the number of physical names")?;
                let n = c.usize("number of physical names")?;
                for _ in 0..n {
                    c.begin_line("a physical name")?;
                    let dim = c.usize("physical dimension")?;
                    let tag = c.i64("physical tag")?;
                    let name = c.token("physical name")?;
                    let name = name.trim_matches('"').to_owned();
                    raw.names.insert((dim, tag), name);
                }
                c.expect_line("$EndPhysicalNames")?;
            }
            "$Entities" if v4 => {
                c.begin_line("entity counts")?;
                let counts = [
                    c.usize("number of points")?,
                    c.usize("number of curves")?,
                    c.usize("number of surfaces")?,
                    c.usize("number of volumes")?,
                ];
                for (dim, &n) in counts.iter().enumerate() {
                    for _ in 0..n {
                        c.begin_line("an entity")?;
                        let tag = c.i64("entity tag")?;
                        let n_coords = if dim == 0 { 3 } else { 6 };
                        for _ in 0..n_coords {
                            c.f64("entity coordinate")?;
                        }
                        let n_phys = c.usize("number of physical tags")?;
                        let phys = (0..n_phys).map(|_| c.i64("physical tag")).collect::<Result<Vec<_>, _>>()?;
                        entity_phys.insert((dim, tag), phys);
                    }
                }
                c.expect_line("$EndEntities")?;
            }
            "$Nodes" => {
                seen_nodes = true;
                if v4 {
                    read_nodes_v4(&mut c, &mut raw, limits)?
                } else {
                    read_nodes_v2(&mut c, &mut raw, limits)?
                }
                c.expect_line("$EndNodes")?;
            }
            "$Elements" => {
                seen_elements = true;
                if v4 {
                    read_elements_v4(&mut c, &mut raw, &entity_phys, limits)?
                } else {
                    read_elements_v2(&mut c, &mut raw, limits)?
                }
                c.expect_line("$EndElements")?;
            }
            s if s.starts_with('$') && !s.starts_with("$End") => {
                let end = format!("$End{}", &s[1..]);
                c.skip_section(&end, line)?;
            }
            other => return Err(syntax(line, format!("expected a section such as $Nodes, found '{}'", truncate(other))).into()),
        }
    }
    if !seen_nodes {
        return Err(syntax(c.last_line(), "the file has no $Nodes section").into());
    }
    if !seen_elements {
        return Err(syntax(c.last_line(), "the file has no $Elements section").into());
    }
    Ok((raw, version))
}

fn read_nodes_v2(c: &mut Cursor<'_>, raw: &mut Raw, limits: &ReadLimits) -> Result<(), ReadError> {
    c.begin_line("the number of nodes")?;
    let n = c.usize("number of nodes")?;
    if n > limits.max_nodes {
        return Err(ReadError::TooManyNodes { n_nodes: n, max_nodes: limits.max_nodes });
    }
    raw.nodes.reserve(n);
    for _ in 0..n {
        c.begin_line("a node")?;
        let tag = c.usize("node tag")? as u64;
        let x = c.f64("node x")?;
        let y = c.f64("node y")?;
        let z = c.f64("node z")?;
        c.end_of_line()?;
        raw.nodes.push((tag, [x, y, z]));
    }
    Ok(())
}

fn read_nodes_v4(c: &mut Cursor<'_>, raw: &mut Raw, limits: &ReadLimits) -> Result<(), ReadError> {
    c.begin_line("the node block header")?;
    let n_blocks = c.usize("number of entity blocks")?;
    let n_nodes = c.usize("number of nodes")?;
    if n_nodes > limits.max_nodes {
        return Err(ReadError::TooManyNodes { n_nodes, max_nodes: limits.max_nodes });
    }
    raw.nodes.reserve(n_nodes);
    for _ in 0..n_blocks {
        c.begin_line("a node entity block")?;
        let _dim = c.usize("entity dimension")?;
        let _tag = c.i64("entity tag")?;
        let parametric = c.usize("parametric flag")?;
        let n = c.usize("number of nodes in block")?;
        if parametric != 0 {
            return Err(syntax(c.line, "parametric node coordinates are not supported").into());
        }
        if n > n_nodes - raw.nodes.len() {
            return Err(syntax(c.line, format!("node blocks hold more nodes than the {n_nodes} announced")).into());
        }
        let mut tags = Vec::with_capacity(n);
        for _ in 0..n {
            c.begin_line("a node tag")?;
            tags.push(c.usize("node tag")? as u64);
            c.end_of_line()?;
        }
        for tag in tags {
            c.begin_line("node coordinates")?;
            let x = c.f64("node x")?;
            let y = c.f64("node y")?;
            let z = c.f64("node z")?;
            c.end_of_line()?;
            raw.nodes.push((tag, [x, y, z]));
        }
    }
    if raw.nodes.len() != n_nodes {
        return Err(syntax(c.line, format!("{n_nodes} nodes announced but {} found", raw.nodes.len())).into());
    }
    Ok(())
}

fn element_nodes(c: &mut Cursor<'_>, etype: usize, three_d: bool) -> Result<Option<Vec<u64>>, MshError> {
    let n = match etype {
        1 => 2,
        2 => 3,
        15 => 1,
        4 if three_d => 4,
        3 | 5 | 6 | 7 | 11 | 12 | 13 | 14 | 17 | 18 | 19 | 29 | 30 | 31 if three_d => {
            return Err(syntax(c.line, format!("element type {etype} is not supported: only linear tetrahedra (type 4) make a 3D mesh")));
        }
        3 | 8 | 9 | 10 | 16 | 20 | 21 | 22 | 23 | 24 | 25 => {
            return Err(syntax(c.line, format!("element type {etype} is not supported: only linear triangles (type 2) make the mesh")));
        }
        _ => return Ok(None),
    };
    let nodes = (0..n).map(|_| c.usize("element node").map(|v| v as u64)).collect::<Result<Vec<_>, _>>()?;
    c.end_of_line()?;
    Ok(Some(nodes))
}

fn read_elements_v2(c: &mut Cursor<'_>, raw: &mut Raw, limits: &ReadLimits) -> Result<(), ReadError> {
    c.begin_line("the number of elements")?;
    let n = c.usize("number of elements")?;
    if n > limits.max_elements {
        return Err(ReadError::TooManyElements { n_elements: n });
    }
    for _ in 0..n {
        c.begin_line("an element")?;
        let tag = c.usize("element tag")? as u64;
        let etype = c.usize("element type")?;
        let n_tags = c.usize("number of tags")?;
        let tags = (0..n_tags).map(|_| c.i64("element tag value")).collect::<Result<Vec<_>, _>>()?;
        let phys = tags.first().copied().filter(|&t| t != 0);
        let line = c.line;
        let Some(nodes) = element_nodes(c, etype, limits.three_d)? else { continue };
        push_element(raw, etype, nodes, phys.into_iter().collect(), tag, line, limits.three_d);
    }
    Ok(())
}

fn read_elements_v4(
    c: &mut Cursor<'_>,
    raw: &mut Raw,
    entity_phys: &HashMap<(usize, i64), Vec<i64>>,
    limits: &ReadLimits,
) -> Result<(), ReadError> {
    c.begin_line("the element block header")?;
    let n_blocks = c.usize("number of entity blocks")?;
    let n_elements = c.usize("number of elements")?;
    if n_elements > limits.max_elements {
        return Err(ReadError::TooManyElements { n_elements });
    }
    let mut seen = 0usize;
    for _ in 0..n_blocks {
        c.begin_line("an element entity block")?;
        let dim = c.usize("entity dimension")?;
        let tag = c.i64("entity tag")?;
        let etype = c.usize("element type")?;
        let n = c.usize("number of elements in block")?;
        if n > n_elements - seen {
            return Err(syntax(c.line, format!("element blocks hold more elements than the {n_elements} announced")).into());
        }
        seen += n;
        let phys = entity_phys.get(&(dim, tag)).cloned().unwrap_or_default();
        for _ in 0..n {
            c.begin_line("an element")?;
            let tag = c.usize("element tag")? as u64;
            let line = c.line;
            let Some(nodes) = element_nodes(c, etype, limits.three_d)? else { continue };
            push_element(raw, etype, nodes, phys.clone(), tag, line, limits.three_d);
        }
    }
    if seen != n_elements {
        return Err(syntax(c.line, format!("{n_elements} elements announced but {seen} found")).into());
    }
    Ok(())
}

fn push_element(raw: &mut Raw, etype: usize, nodes: Vec<u64>, phys: Vec<i64>, tag: u64, line: usize, three_d: bool) {
    match etype {
        4 if three_d => raw.tets.push(([nodes[0], nodes[1], nodes[2], nodes[3]], phys.first().copied(), tag, line)),
        2 if !three_d => raw.triangles.push(([nodes[0], nodes[1], nodes[2]], phys.first().copied(), line)),
        1 | 2 | 15 => {
            let dim = match etype {
                1 => 1,
                2 => 2,
                _ => 0,
            };
            for p in phys {
                raw.groups.push((dim, p, nodes.clone()));
            }
        }
        _ => {}
    }
}

fn build(raw: Raw, version: String, limits: &MeshLimits) -> Result<MshMesh, MshError> {
    let mut index_of_tag: HashMap<u64, usize> = HashMap::with_capacity(raw.nodes.len());
    for (i, (tag, _)) in raw.nodes.iter().enumerate() {
        if index_of_tag.insert(*tag, i).is_some() {
            return Err(syntax(0, format!("node tag {tag} is defined twice")));
        }
    }
    // Keep nodes used by triangles, in file order.
    let mut used = vec![false; raw.nodes.len()];
    for (tri, _, line) in &raw.triangles {
        for t in tri {
            let i =
                *index_of_tag.get(t).ok_or_else(|| syntax(*line, format!("triangle uses node tag {t}, which $Nodes does not define")))?;
            used[i] = true;
        }
    }
    let mut new_index = vec![usize::MAX; raw.nodes.len()];
    let mut nodes = Vec::new();
    let mut node_tags = Vec::new();
    for (i, (tag, xy)) in raw.nodes.iter().enumerate() {
        if used[i] {
            new_index[i] = nodes.len();
            nodes.push([xy[0], xy[1]]);
            node_tags.push(*tag);
        }
    }
    // Regions: 2D physical tags in increasing order; untagged triangles form "default".
    let mut region_tags: Vec<Option<i64>> = raw.triangles.iter().map(|t| t.1).collect();
    region_tags.sort();
    region_tags.dedup();
    let region_names: Vec<String> = region_tags
        .iter()
        .map(|t| match t {
            None => "default".to_owned(),
            Some(t) => raw.names.get(&(2, *t)).cloned().unwrap_or_else(|| format!("physical{t}")),
        })
        .collect();
    let triangles: Vec<[usize; 3]> = raw.triangles.iter().map(|(tri, _, _)| tri.map(|t| new_index[index_of_tag[&t]])).collect();
    let regions: Vec<usize> = raw.triangles.iter().map(|(_, p, _)| region_tags.binary_search(p).expect("collected above")).collect();
    let mut sets: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for (dim, p, tags) in &raw.groups {
        let name = raw.names.get(&(*dim, *p)).cloned().unwrap_or_else(|| format!("physical{p}"));
        let set = sets.entry(name).or_default();
        for t in tags {
            let i = *index_of_tag
                .get(t)
                .ok_or_else(|| syntax(0, format!("boundary element uses node tag {t}, which $Nodes does not define")))?;
            if new_index[i] != usize::MAX {
                set.push(new_index[i]);
            }
        }
    }
    for v in sets.values_mut() {
        v.sort_unstable();
        v.dedup();
    }
    let mesh = Mesh::with_regions(nodes, triangles, regions, region_names, sets, limits)?;
    Ok(MshMesh { mesh, node_tags, version })
}

fn build3d(raw: Raw, version: String, limits: &TetMeshLimits) -> Result<MshTetMesh, MshError> {
    let mut index_of_tag: HashMap<u64, usize> = HashMap::with_capacity(raw.nodes.len());
    for (i, (tag, _)) in raw.nodes.iter().enumerate() {
        if index_of_tag.insert(*tag, i).is_some() {
            return Err(syntax(0, format!("node tag {tag} is defined twice")));
        }
    }
    // Keep nodes used by tetrahedra, in file order.
    let mut used = vec![false; raw.nodes.len()];
    for (tet, _, tag, line) in &raw.tets {
        for t in tet {
            let i = *index_of_tag.get(t).ok_or_else(|| {
                syntax(*line, format!("tetrahedron with element tag {tag} uses node tag {t}, which $Nodes does not define"))
            })?;
            used[i] = true;
        }
    }
    let mut new_index = vec![usize::MAX; raw.nodes.len()];
    let mut nodes = Vec::new();
    let mut node_tags = Vec::new();
    for (i, (tag, xyz)) in raw.nodes.iter().enumerate() {
        if used[i] {
            new_index[i] = nodes.len();
            nodes.push(*xyz);
            node_tags.push(*tag);
        }
    }
    let tets: Vec<[usize; 4]> = raw.tets.iter().map(|(tet, ..)| tet.map(|t| new_index[index_of_tag[&t]])).collect();
    // Gmsh's tetrahedra are positively oriented; a negative one (beyond round-off) is a broken file.
    for (k, t) in tets.iter().enumerate() {
        if t.iter().enumerate().any(|(i, n)| t[..i].contains(n)) {
            continue; // named by the mesh validation below
        }
        let p = t.map(|i| nodes[i]);
        let v = signed_volume_m3(p[0], p[1], p[2], p[3]);
        let h = longest_edge_m(p);
        if v < -crate::d3::mesh::DEGENERATE_VOLUME_TOL * h * h * h {
            let (_, _, tag, line) = raw.tets[k];
            return Err(MshError::Tetrahedron {
                line,
                tag,
                message: format!("it is inverted (negative volume {v:e} m³); Gmsh writes positively oriented tetrahedra"),
            });
        }
    }
    let mut region_tags: Vec<Option<i64>> = raw.tets.iter().map(|t| t.1).collect();
    region_tags.sort();
    region_tags.dedup();
    let region_names: Vec<String> = region_tags
        .iter()
        .map(|t| match t {
            None => "default".to_owned(),
            Some(t) => raw.names.get(&(3, *t)).cloned().unwrap_or_else(|| format!("physical{t}")),
        })
        .collect();
    let regions: Vec<usize> = raw.tets.iter().map(|(_, p, ..)| region_tags.binary_search(p).expect("collected above")).collect();
    let mut sets: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for (dim, p, tags) in &raw.groups {
        let name = raw.names.get(&(*dim, *p)).cloned().unwrap_or_else(|| format!("physical{p}"));
        let set = sets.entry(name).or_default();
        for t in tags {
            let i = *index_of_tag
                .get(t)
                .ok_or_else(|| syntax(0, format!("boundary element uses node tag {t}, which $Nodes does not define")))?;
            if new_index[i] != usize::MAX {
                set.push(new_index[i]);
            }
        }
    }
    let element_tags: Vec<u64> = raw.tets.iter().map(|t| t.2).collect();
    let mesh = TetMesh::with_regions(nodes, tets, regions, region_names, sets, limits).map_err(|e| {
        let tet_idx = match &e {
            TetMeshError::RepeatedNode { tet_idx, .. }
            | TetMeshError::Degenerate { tet_idx, .. }
            | TetMeshError::NodeOutOfRange { tet_idx, .. } => Some(*tet_idx),
            TetMeshError::DuplicateTet { second_idx, .. } => Some(*second_idx),
            _ => None,
        };
        match tet_idx {
            Some(k) => {
                let (_, _, tag, line) = raw.tets[k];
                let message = match &e {
                    TetMeshError::DuplicateTet { first_idx, .. } => {
                        format!(
                            "it has the same nodes as the tetrahedron with element tag {} (line {})",
                            raw.tets[*first_idx].2, raw.tets[*first_idx].3
                        )
                    }
                    other => other.to_string(),
                };
                MshError::Tetrahedron { line, tag, message }
            }
            None => e.into(),
        }
    })?;
    Ok(MshTetMesh { mesh, node_tags, element_tags, version })
}

#[cfg(test)]
mod tests {
    use super::*;

    const V22: &str = include_str!("../testdata/inclusion_v22.msh");
    const V41: &str = include_str!("../testdata/inclusion_v41.msh");

    const TETS_V22: &str = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n3\n2 3 \"bottom\"\n3 1 \"tissue\"\n3 2 \"lesion\"\n$EndPhysicalNames\n\
        $Nodes\n6\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 9 9 9\n6 1 1 1\n$EndNodes\n\
        $Elements\n4\n1 15 2 0 5 5\n2 2 2 3 1 1 2 3\n3 4 2 1 1 1 2 3 4\n4 4 2 2 2 2 3 4 6\n$EndElements\n";
    const TETS_V41: &str = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n3\n2 3 \"bottom\"\n3 1 \"tissue\"\n3 2 \"lesion\"\n$EndPhysicalNames\n\
        $Entities\n0 0 1 2\n1 0 0 0 1 1 0 1 3 0\n1 0 0 0 1 1 1 1 1 0\n2 0 0 0 1 1 1 1 2 0\n$EndEntities\n\
        $Nodes\n1 6 1 6\n3 1 0 6\n1\n2\n3\n4\n5\n6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n9 9 9\n1 1 1\n$EndNodes\n\
        $Elements\n3 3 1 4\n2 1 2 1\n2 1 2 3\n3 1 4 1\n3 1 2 3 4\n3 2 4 1\n4 2 3 4 6\n$EndElements\n";

    #[test]
    fn tetrahedra_in_both_versions_give_the_same_mesh() {
        let lim = TetMeshLimits::default();
        let a = parse_msh3d(TETS_V22, &lim).unwrap();
        let b = parse_msh3d(TETS_V41, &lim).unwrap();
        assert_eq!(a.mesh, b.mesh);
        assert_eq!((a.version.as_str(), b.version.as_str()), ("2.2", "4.1"));
        assert_eq!(a.node_tags, vec![1, 2, 3, 4, 6]);
        assert_eq!(a.element_tags, vec![3, 4]);
        assert_eq!(b.element_tags, vec![3, 4]);
        let m = &a.mesh;
        assert_eq!(m.tets(), &[[0, 1, 2, 3], [1, 2, 3, 4]]);
        assert_eq!(m.region_names(), &["tissue".to_owned(), "lesion".to_owned()]);
        assert_eq!(m.region_of_tet(), &[0, 1]);
        assert_eq!(m.boundary_set("bottom").unwrap(), &[0, 1, 2]);
        assert_eq!(m.nodes_m()[4], [1.0, 1.0, 1.0]);
        // The 2D reader, unchanged, takes only the triangles of the same file and skips tetrahedra.
        let flat = parse_msh(TETS_V22, &MeshLimits::default()).unwrap();
        assert_eq!(flat.mesh.triangles(), &[[0, 1, 2]]);
    }

    #[test]
    fn bad_tetrahedra_name_their_line_and_tag() {
        let lim = TetMeshLimits::default();
        let inverted = TETS_V22.replace("3 4 2 1 1 1 2 3 4", "3 4 2 1 1 1 3 2 4");
        let e = parse_msh3d(&inverted, &lim).unwrap_err();
        assert!(e.to_string().starts_with("MSH line 23: tetrahedron with element tag 3: it is inverted (negative volume"), "{e}");
        let flat = TETS_V22.replace("6 1 1 1", "6 0.5 0.5 0");
        let e = parse_msh3d(&flat, &lim).unwrap_err();
        assert!(
            e.to_string().starts_with("MSH line 24: tetrahedron with element tag 4: tetrahedron 1 (nodes [1, 2, 3, 4]) is degenerate"),
            "{e}"
        );
        let twice = TETS_V22.replace("4 4 2 2 2 2 3 4 6", "4 4 2 2 2 4 3 2 1");
        let e = parse_msh3d(&twice, &lim).unwrap_err();
        assert_eq!(
            e.to_string(),
            "MSH line 24: tetrahedron with element tag 4: it has the same nodes as the tetrahedron with element tag 3 (line 23)"
        );
        let hexa = TETS_V22.replace("4 4 2 2 2 2 3 4 6", "4 5 2 2 2 1 2 3 4 5 6 1 2");
        let e = parse_msh3d(&hexa, &lim).unwrap_err();
        assert!(e.to_string().starts_with("MSH line 24: element type 5 is not supported: only linear tetrahedra"), "{e}");
        let missing = TETS_V41.replace("4 2 3 4 6", "4 2 3 4 66");
        let e = parse_msh3d(&missing, &lim).unwrap_err();
        assert!(e.to_string().contains("element tag 4 uses node tag 66, which $Nodes does not define"), "{e}");
        let small = TetMeshLimits { max_nodes: 10, max_tets: 1 };
        let e = parse_msh3d(TETS_V22, &small).unwrap_err();
        assert!(e.to_string().contains("2 tetrahedra, over the limit of 1"), "{e}");
    }

    #[test]
    fn issue_35_a_mesh_error_says_its_words_once_and_quotes_a_token_clipped() {
        // The whole chain (what `{:#}` prints) holds the mesh's words once, not "…: … overlap".
        let chain = |e: &MshError| {
            let mut out = e.to_string();
            let mut src = std::error::Error::source(e);
            while let Some(s) = src {
                out.push_str(": ");
                out.push_str(&s.to_string());
                src = s.source();
            }
            out
        };
        let small = TetMeshLimits { max_nodes: 10, max_tets: 1 };
        let m = chain(&parse_msh3d(TETS_V22, &small).unwrap_err());
        assert_eq!(m.matches("2 tetrahedra, over the limit of 1").count(), 1, "{m}");
        let flat = MeshLimits { max_nodes: 2, ..MeshLimits::default() };
        let m = chain(&parse_msh(V22, &flat).unwrap_err());
        assert_eq!(m.matches("over the limit of 2").count(), 1, "{m}");
        // A 100 kB token is quoted clipped.
        let long = TETS_V22.replace("2 1 0 0\n", &format!("2 {} 0 0\n", "x".repeat(100_000)));
        let m = chain(&parse_msh3d(&long, &TetMeshLimits::default()).unwrap_err());
        assert!(m.contains("must be a number, found 'xxxx") && m.len() < 200, "{m}");
    }

    #[test]
    fn both_versions_give_the_same_mesh() {
        let a = parse_msh(V22, &MeshLimits::default()).unwrap();
        let b = parse_msh(V41, &MeshLimits::default()).unwrap();
        assert_eq!(a.version, "2.2");
        assert_eq!(b.version, "4.1");
        assert_eq!(a.mesh, b.mesh);
        assert_eq!(a.node_tags, b.node_tags);
        let m = &a.mesh;
        assert_eq!(m.region_names(), &["tissue".to_owned(), "inclusion".to_owned()]);
        // The 0.1 m square is tiled exactly.
        let area: f64 = (0..m.n_triangles()).map(|t| m.signed_area_m2(t).abs()).sum();
        assert!((area - 0.01).abs() < 1e-12, "area {area}");
        // The inclusion is the disc of radius 0.015 around (0.05, 0.04), up to polygonal error.
        let inc: f64 = (0..m.n_triangles()).filter(|&t| m.region_of_tri()[t] == 1).map(|t| m.signed_area_m2(t).abs()).sum();
        let disc = std::f64::consts::PI * 0.015f64.powi(2);
        assert!((inc - disc).abs() < 0.02 * disc, "inclusion area {inc} vs {disc}");
        let bottom = m.boundary_set("fixed_bottom").unwrap();
        assert!(bottom.len() > 5 && bottom.iter().all(|&n| m.nodes_m()[n][1].abs() < 1e-12));
        let needle = m.boundary_set("needle").unwrap();
        assert!(needle.iter().all(|&n| (m.nodes_m()[n][0] - 0.05).abs() < 1e-9));
        assert_eq!(m.n_nodes(), 694);
        assert_eq!(a.node_tags, (1..=694).collect::<Vec<u64>>());
    }

    #[test]
    fn unused_nodes_are_dropped_and_sets_named() {
        let text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n1 7 \"fixed edge\"\n$EndPhysicalNames\n\
            $Nodes\n5\n10 0 0 0\n11 9 9 0\n12 1 0 0\n13 0 1 0\n14 1 1 0\n$EndNodes\n\
            $Elements\n4\n1 15 2 0 1 11\n2 1 2 7 1 10 12\n3 2 2 0 1 10 12 14\n4 2 2 0 1 10 14 13\n$EndElements\n";
        let m = parse_msh(text, &MeshLimits::default()).unwrap();
        assert_eq!(m.node_tags, vec![10, 12, 13, 14]);
        assert_eq!(m.mesh.triangles(), &[[0, 1, 3], [0, 3, 2]]);
        assert_eq!(m.mesh.boundary_set("fixed edge").unwrap(), &[0, 1]);
        assert_eq!(m.mesh.region_names(), &["default".to_owned()]);
    }

    #[test]
    fn malformed_files_name_the_line() {
        let lim = MeshLimits::default();
        let e = parse_msh("$MeshFormat\n3.0 0 8\n$EndMeshFormat\n", &lim).unwrap_err();
        assert_eq!(e.to_string(), "MSH line 2: MSH version 3.0 is not supported; use 2.2 or 4.1");
        let e = parse_msh("$MeshFormat\n2.2 1 8\n$EndMeshFormat\n", &lim).unwrap_err();
        assert!(e.to_string().contains("line 2: binary"), "{e}");
        let bad = V22.replacen("2 0.05 0.1 0", "2 0.05 zero 0", 1);
        let e = parse_msh(&bad, &lim).unwrap_err();
        assert_eq!(e.to_string(), "MSH line 14: node y must be a number, found 'zero'");
        let lines: Vec<&str> = V22.lines().collect();
        let truncated = lines[..100].join("\n");
        let e = parse_msh(&truncated, &lim).unwrap_err();
        assert!(e.to_string().contains("unexpected end of file"), "{e}");
        // A triangle pointing at an undefined node.
        let idx = lines.iter().rposition(|l| l.split_whitespace().nth(1) == Some("2")).unwrap();
        let mut broken: Vec<String> = lines.iter().map(|s| s.to_string()).collect();
        let mut parts: Vec<&str> = lines[idx].split_whitespace().collect();
        let last = parts.len() - 1;
        parts[last] = "99999";
        broken[idx] = parts.join(" ");
        let e = parse_msh(&broken.join("\n"), &lim).unwrap_err();
        assert_eq!(e.to_string(), format!("MSH line {}: triangle uses node tag 99999, which $Nodes does not define", idx + 1));
        let e = parse_msh("hello", &lim).unwrap_err();
        assert_eq!(e.to_string(), "MSH line 1: expected $MeshFormat, found 'hello'");
        let quad = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 0\n$EndNodes\n$Elements\n1\n1 3 0 1 1 1 1\n$EndElements\n";
        let e = parse_msh(quad, &lim).unwrap_err();
        assert!(e.to_string().starts_with("MSH line 10: element type 3 is not supported"), "{e}");
        let small = MeshLimits { max_nodes: 100, max_triangles: 100 };
        let e = parse_msh(V41, &small).unwrap_err();
        assert!(e.to_string().contains("over the limit of 100"), "{e}");
    }

    /// Found while writing the fuzzing harness (issue 13): a later block announcing usize::MAX
    /// entries overflowed the running count (a panic in debug builds) instead of being an error.
    #[test]
    fn issue_13_huge_block_counts_are_errors() {
        let (lim, max) = (MeshLimits::default(), usize::MAX);
        let nodes = format!("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n2 3 1 3\n2 1 0 1\n1\n0 0 0\n2 1 0 {max}\n$EndNodes\n");
        let e = parse_msh(&nodes, &lim).unwrap_err();
        assert_eq!(e.to_string(), "MSH line 9: node blocks hold more nodes than the 3 announced");
        let elements = format!(
            "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n0 1 0\n$EndNodes\n\
             $Elements\n2 2 1 2\n2 1 2 1\n1 1 2 3\n2 1 2 {max}\n$EndElements\n"
        );
        let e = parse_msh(&elements, &lim).unwrap_err();
        assert_eq!(e.to_string(), "MSH line 18: element blocks hold more elements than the 2 announced");
    }
}
