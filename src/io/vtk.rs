//! VTK output (XML `.vtu` and legacy `.vtk`, ASCII; binary VTU through `vtu_binary`) of line,
//! triangle and tet cells with integer cell data, and a reader for the same files so
//! `tetrafoil quality` can check them: ASCII or appended VTU data, one unstructured-grid piece, cells of VTK type 3 (line), 5 (triangle) and 10
//! (tetrahedron); any other cell type is an error naming it. The VTU side is parsed as XML
//! (`quick-xml`); counts in a file are checked against the data that follows and never size
//! an allocation.

pub use super::cells::CellNodes;
use super::vtu_binary::{decode, numbers as vtu_numbers, vtk_type, FromNumber, Layout, Number};
use super::write_atomic;
use glam::DVec3;
use quick_xml::escape::escape;
use quick_xml::events::{BytesStart, Event};
use quick_xml::Reader;
use std::borrow::Cow;
use std::io::Write;
use std::path::Path;

/// Cells of one kind: 2 (segments), 3 (triangles) or 4 (tets) nodes each.
///
/// A cell is anything with [`CellNodes`]: the reader makes `Vec<usize>`s; the volume writer
/// passes views of the mesh's cells rather than an allocation per cell.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CellMesh<C = Vec<usize>> {
    pub points: Vec<DVec3>,
    pub cells: Vec<C>,
    /// Named integer cell data (e.g. "edge", "face", "region").
    pub cell_data: Vec<(String, Vec<i64>)>,
}

/// XML `.vtu` (ASCII, or binary: appended zlib-compressed data) or legacy `.vtk`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Flavour {
    Xml,
    XmlBinary,
    Legacy,
}

/// Named real-valued cell data (quality measures), beside the integer data of [`CellMesh`].
pub type RealData = [(String, Vec<f64>)];

/// Write `.vtu` or `.vtk` by extension.
pub fn write(path: &Path, mesh: &CellMesh) -> std::io::Result<()> {
    let flavour = match path.extension().and_then(|e| e.to_str()) {
        Some("vtk") => Flavour::Legacy,
        _ => Flavour::Xml,
    };
    write_with(path, mesh, &[], flavour)
}

/// Write `mesh` with extra real cell data, in the given flavour whatever the extension.
pub fn write_with<C: CellNodes>(
    path: &Path,
    mesh: &CellMesh<C>,
    reals: &RealData,
    flavour: Flavour,
) -> std::io::Result<()> {
    let lengths = mesh.cell_data.iter().map(|(n, d)| (n, d.len()));
    let real_lengths = reals.iter().map(|(n, d)| (n, d.len()));
    if let Some((name, n)) = lengths
        .chain(real_lengths)
        .find(|&(_, n)| n != mesh.cells.len())
    {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            format!(
                "cell data '{name}' has {n} values for {} cells",
                mesh.cells.len()
            ),
        ));
    }
    // A legacy SCALARS line is `SCALARS name type 1`: a name with a space would not read back.
    if flavour == Flavour::Legacy {
        let ints = mesh.cell_data.iter().map(|(n, _)| n);
        let mut names = ints.chain(reals.iter().map(|(n, _)| n));
        if let Some(name) = names.find(|n| n.is_empty() || n.contains(char::is_whitespace)) {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                format!(
                    "cell data name '{name}' is empty or has a space: legacy VTK can't hold it"
                ),
            ));
        }
    }
    match flavour {
        Flavour::Legacy => write_atomic(path, |w| write_legacy(w, mesh, reals)),
        Flavour::Xml => write_atomic(path, |w| write_vtu(w, mesh, reals)),
        Flavour::XmlBinary => write_atomic(path, |w| {
            super::vtu_binary::write_vtu(w, &mesh.points, &mesh.cells, &mesh.cell_data, reals)
        }),
    }
}

fn write_vtu<C: CellNodes>(
    w: &mut dyn Write,
    m: &CellMesh<C>,
    reals: &RealData,
) -> std::io::Result<()> {
    writeln!(w, r#"<?xml version="1.0"?>"#)?;
    writeln!(
        w,
        r#"<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian">"#
    )?;
    writeln!(w, "<UnstructuredGrid>")?;
    writeln!(
        w,
        r#"<Piece NumberOfPoints="{}" NumberOfCells="{}">"#,
        m.points.len(),
        m.cells.len()
    )?;
    writeln!(
        w,
        r#"<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">"#
    )?;
    for p in &m.points {
        writeln!(w, "{:e} {:e} {:e}", p.x, p.y, p.z)?;
    }
    writeln!(w, "</DataArray></Points>")?;
    writeln!(w, "<Cells>")?;
    writeln!(
        w,
        r#"<DataArray type="Int64" Name="connectivity" format="ascii">"#
    )?;
    for c in &m.cells {
        let s: Vec<String> = c.nodes().map(|i| i.to_string()).collect();
        writeln!(w, "{}", s.join(" "))?;
    }
    writeln!(w, "</DataArray>")?;
    writeln!(
        w,
        r#"<DataArray type="Int64" Name="offsets" format="ascii">"#
    )?;
    let mut off = 0;
    for c in &m.cells {
        off += c.node_count();
        writeln!(w, "{off}")?;
    }
    writeln!(w, "</DataArray>")?;
    writeln!(w, r#"<DataArray type="UInt8" Name="types" format="ascii">"#)?;
    for c in &m.cells {
        writeln!(w, "{}", vtk_type(c.node_count()))?;
    }
    writeln!(w, "</DataArray>")?;
    writeln!(w, "</Cells>")?;
    writeln!(w, "<CellData>")?;
    for (name, data) in &m.cell_data {
        writeln!(
            w,
            r#"<DataArray type="Int64" Name="{}" format="ascii">"#,
            escape(name)
        )?;
        for d in data {
            writeln!(w, "{d}")?;
        }
        writeln!(w, "</DataArray>")?;
    }
    for (name, data) in reals {
        writeln!(
            w,
            r#"<DataArray type="Float64" Name="{}" format="ascii">"#,
            escape(name)
        )?;
        for d in data {
            writeln!(w, "{d:e}")?;
        }
        writeln!(w, "</DataArray>")?;
    }
    writeln!(w, "</CellData>")?;
    writeln!(w, "</Piece></UnstructuredGrid></VTKFile>")
}

fn write_legacy<C: CellNodes>(
    w: &mut dyn Write,
    m: &CellMesh<C>,
    reals: &RealData,
) -> std::io::Result<()> {
    writeln!(w, "# vtk DataFile Version 3.0")?;
    writeln!(w, "tetrafoil")?;
    writeln!(w, "ASCII")?;
    writeln!(w, "DATASET UNSTRUCTURED_GRID")?;
    writeln!(w, "POINTS {} double", m.points.len())?;
    for p in &m.points {
        writeln!(w, "{:e} {:e} {:e}", p.x, p.y, p.z)?;
    }
    let size: usize = m.cells.iter().map(|c| c.node_count() + 1).sum();
    writeln!(w, "CELLS {} {size}", m.cells.len())?;
    for c in &m.cells {
        let s: Vec<String> = c.nodes().map(|i| i.to_string()).collect();
        writeln!(w, "{} {}", c.node_count(), s.join(" "))?;
    }
    writeln!(w, "CELL_TYPES {}", m.cells.len())?;
    for c in &m.cells {
        writeln!(w, "{}", vtk_type(c.node_count()))?;
    }
    if !m.cell_data.is_empty() || !reals.is_empty() {
        writeln!(w, "CELL_DATA {}", m.cells.len())?;
        for (name, data) in &m.cell_data {
            writeln!(w, "SCALARS {name} int 1")?;
            writeln!(w, "LOOKUP_TABLE default")?;
            for d in data {
                writeln!(w, "{d}")?;
            }
        }
        for (name, data) in reals {
            writeln!(w, "SCALARS {name} double 1")?;
            writeln!(w, "LOOKUP_TABLE default")?;
            for d in data {
                writeln!(w, "{d:e}")?;
            }
        }
    }
    Ok(())
}

#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    #[error("{path}: {message}")]
    Bad { path: String, message: String },
    #[error("{path}: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
}

/// Read a `.vtu` or legacy `.vtk` file of the kind [`write`] produces: ASCII, an unstructured
/// grid of lines, triangles and tetrahedra (VTK cell types 3, 5 and 10) with integer cell data.
///
/// - VTU: `VTKFile type="UnstructuredGrid"` holding one `Piece`; its `Points` array (3
///   components), the `Cells` arrays `connectivity`, `offsets` and `types`, and every integer
///   one-component `CellData` array (into [`CellMesh::cell_data`]). Each of these must have
///   `format="ascii"` or `"appended"` (raw `AppendedData`, zlib-compressed or not; inline
///   base64 `"binary"` is refused) and as many values as the piece's `NumberOfPoints` /
///   `NumberOfCells` say. Real or multi-component cell data, `PointData` and `FieldData` are
///   skipped (appended ones are not decoded).
/// - Legacy: `ASCII`, `DATASET UNSTRUCTURED_GRID`, `POINTS`, `CELLS`, `CELL_TYPES`, and the
///   integer one-component `SCALARS` of `CELL_DATA` (into `cell_data`); other sections are
///   skipped. A file without `CELL_TYPES` is read as before the types were read: a cell's
///   kind is taken from its node count (2 a line, 3 a triangle, 4 a tetrahedron, so a quad
///   without its type reads as a tet), and a cell of any other size is an error.
///
/// A cell of another type (wedge, quad, ...), or with a node count its type does not have, is
/// an error naming the cell and the type. Real cell data that [`write_with`] adds is not read
/// back: `read` after [`write`] gives the [`CellMesh`] written.
pub fn read(path: &Path) -> Result<CellMesh, ReadError> {
    let bytes = std::fs::read(path).map_err(|source| ReadError::Io {
        path: path.display().to_string(),
        source,
    })?;
    let bad = |message: String| ReadError::Bad {
        path: path.display().to_string(),
        message,
    };
    if bytes.starts_with(b"# vtk") {
        read_legacy(&String::from_utf8_lossy(&bytes)).map_err(bad)
    } else {
        read_vtu(&bytes).map_err(bad)
    }
}

/// The cell kinds [`CellMesh`] holds, by VTK type: (type, nodes).
const CELL_KINDS: [(i64, usize); 5] = [(3, 2), (5, 3), (10, 4), (13, 6), (14, 5)];

/// A VTK cell type in words, e.g. "a wedge (VTK type 13)", or "VTK type 99" when unnamed.
fn cell_type_words(t: i64) -> String {
    let name = match t {
        0 => "empty cell",
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
        15 => "pentagonal prism",
        16 => "hexagonal prism",
        21 => "quadratic edge",
        22 => "quadratic triangle",
        23 => "quadratic quad",
        24 => "quadratic tetrahedron",
        25 => "quadratic hexahedron",
        26 => "quadratic wedge",
        27 => "quadratic pyramid",
        42 => "polyhedron",
        _ => return format!("VTK type {t}"),
    };
    let article = if name.starts_with(['a', 'e', 'i', 'o', 'u']) {
        "an"
    } else {
        "a"
    };
    format!("{article} {name} (VTK type {t})")
}

/// Check every cell's kind (by `types`, one per cell, or by node count when the file has no
/// types) and node indices.
fn check_cells(m: &CellMesh, types: Option<&[i64]>) -> Result<(), String> {
    for (i, c) in m.cells.iter().enumerate() {
        match types {
            Some(types) => {
                let t = types[i];
                let Some(&(_, nodes)) = CELL_KINDS.iter().find(|k| k.0 == t) else {
                    return Err(format!(
                        "cell {i} is {}; tetrafoil reads lines, triangles, tetrahedra, \
                         wedges (prisms) and pyramids",
                        cell_type_words(t)
                    ));
                };
                if c.len() != nodes {
                    return Err(format!(
                        "cell {i} is {} but has {} nodes, not {nodes}",
                        cell_type_words(t),
                        c.len()
                    ));
                }
            }
            None => {
                if !CELL_KINDS.iter().any(|k| k.1 == c.len()) {
                    return Err(format!(
                        "cell {i} has {} nodes and the file gives no cell types; tetrafoil \
                         reads 2-node lines, 3-node triangles, 4-node tetrahedra, 5-node \
                         pyramids and 6-node wedges",
                        c.len()
                    ));
                }
            }
        }
        if let Some(&n) = c.iter().find(|&&n| n >= m.points.len()) {
            return Err(format!(
                "cell {i} refers to point {n}, but there are {} points",
                m.points.len()
            ));
        }
    }
    Ok(())
}

fn numbers<T: std::str::FromStr>(s: &str, what: &str) -> Result<Vec<T>, String> {
    s.split_whitespace()
        .map(|x| {
            x.parse::<T>()
                .map_err(|_| format!("bad number '{x}' in {what}"))
        })
        .collect()
}

/// The words of a legacy file after its header.
struct Tokens<'a>(std::iter::Peekable<std::str::SplitWhitespace<'a>>);

impl<'a> Tokens<'a> {
    fn word(&mut self, what: &str) -> Result<&'a str, String> {
        self.0
            .next()
            .ok_or_else(|| format!("the file ends before the {what}"))
    }

    /// A count after a section keyword, e.g. the `10` of `POINTS 10 double`.
    fn count(&mut self, what: &str) -> Result<usize, String> {
        let w = self.word(what)?;
        w.parse().map_err(|_| format!("bad {what} '{w}'"))
    }

    /// Value `i` of `n` that section `key` announced as `things`: an error saying how far the
    /// file got when it ends early.
    fn value<T: std::str::FromStr>(
        &mut self,
        key: &str,
        n: usize,
        things: impl std::fmt::Display,
        i: usize,
    ) -> Result<T, String> {
        let w = self
            .0
            .next()
            .ok_or_else(|| format!("{key} says {n} {things} but the file ends after {i}"))?;
        w.parse()
            .map_err(|_| format!("bad number '{w}' in {key}, at {i} of the {n} {things}"))
    }

    fn next_is(&mut self, keyword: &str) -> bool {
        self.0
            .peek()
            .is_some_and(|w| w.eq_ignore_ascii_case(keyword))
    }
}

/// Legacy attribute data types whose values are integers.
const LEGACY_INTEGERS: [&str; 19] = [
    "bit",
    "unsigned_char",
    "char",
    "unsigned_short",
    "short",
    "unsigned_int",
    "int",
    "unsigned_long",
    "long",
    "vtkidtype",
    "vtktypeint8",
    "vtktypeuint8",
    "vtktypeint16",
    "vtktypeuint16",
    "vtktypeint32",
    "vtktypeuint32",
    "vtktypeint64",
    "vtktypeuint64",
    "vtktypeidtype",
];

fn read_legacy(text: &str) -> Result<CellMesh, String> {
    // "# vtk DataFile Version x.y", a title, ASCII or BINARY, then the data set.
    let mut header = text.splitn(4, '\n');
    let format = header
        .nth(2)
        .map(str::trim)
        .ok_or("the legacy VTK header ends before its ASCII line")?;
    if format.eq_ignore_ascii_case("BINARY") {
        return Err("only ASCII legacy VTK is read: the file says BINARY".into());
    }
    if !format.eq_ignore_ascii_case("ASCII") {
        return Err(format!(
            "bad legacy VTK header: the third line should say ASCII, not '{format}'"
        ));
    }
    let mut t = Tokens(header.next().unwrap_or("").split_whitespace().peekable());
    let dataset = t.word("DATASET")?;
    if !dataset.eq_ignore_ascii_case("DATASET") {
        return Err(format!(
            "bad legacy VTK header: '{dataset}' where DATASET should be"
        ));
    }
    let kind = t.word("DATASET kind")?;
    if !kind.eq_ignore_ascii_case("UNSTRUCTURED_GRID") {
        return Err(format!("not an unstructured grid: DATASET {kind}"));
    }
    let mut m = CellMesh::default();
    let (mut points_seen, mut cells_seen) = (false, false);
    let mut types: Option<Vec<i64>> = None;
    let mut cell_data_count = None;
    // Values per attribute of the current CELL_DATA or POINT_DATA section, and which.
    let mut attribute: Option<(&str, usize)> = None;
    while let Some(key) = t.0.next() {
        let is = |k: &str| key.eq_ignore_ascii_case(k);
        if is("POINTS") {
            if std::mem::replace(&mut points_seen, true) {
                return Err("two POINTS sections".into());
            }
            let n = t.count("POINTS count")?;
            t.word("POINTS data type")?;
            for i in 0..n {
                let mut c = [0.0; 3];
                for x in &mut c {
                    *x = t.value("POINTS", n, "points", i)?;
                }
                m.points.push(DVec3::from_array(c));
            }
        } else if is("CELLS") {
            if std::mem::replace(&mut cells_seen, true) {
                return Err("two CELLS sections".into());
            }
            let n = t.count("CELLS count")?;
            let size = t.count("CELLS list size")?;
            if t.next_is("OFFSETS") {
                return Err(
                    "legacy VTK 5 cells (OFFSETS and CONNECTIVITY) are not read; write the \
                     file as VTU or legacy VTK 4"
                        .into(),
                );
            }
            let mut listed = 0usize;
            for i in 0..n {
                let k: usize = t.value("CELLS", n, "cells", i)?;
                // `k` is from the file: it bounds the loop, which stops when the file does,
                // but it sizes nothing.
                let mut cell = Vec::with_capacity(k.min(4));
                for j in 0..k {
                    cell.push(t.value("CELLS", k, format_args!("nodes of cell {i}"), j)?);
                }
                listed = listed.saturating_add(k.saturating_add(1));
                m.cells.push(cell);
            }
            if listed != size {
                return Err(format!(
                    "CELLS says its list holds {size} numbers, but its {n} cells take {listed}"
                ));
            }
        } else if is("CELL_TYPES") {
            if types.is_some() {
                return Err("two CELL_TYPES sections".into());
            }
            let n = t.count("CELL_TYPES count")?;
            let mut v = Vec::new();
            for i in 0..n {
                v.push(t.value("CELL_TYPES", n, "cells", i)?);
            }
            types = Some(v);
        } else if is("CELL_DATA") || is("POINT_DATA") {
            let n = t.count(&format!("{key} count"))?;
            if is("CELL_DATA") && cell_data_count.replace(n).is_some() {
                return Err("two CELL_DATA sections".into());
            }
            attribute = Some((key, n));
        } else if is("SCALARS") {
            let (section, n) = attribute.ok_or("SCALARS outside CELL_DATA and POINT_DATA")?;
            let name = t.word("SCALARS name")?;
            let data_type = t.word("SCALARS data type")?;
            let components = match t.0.peek().and_then(|w| w.parse::<usize>().ok()) {
                Some(c) => {
                    t.0.next();
                    c
                }
                None => 1,
            };
            if t.next_is("LOOKUP_TABLE") {
                t.0.next();
                t.word("LOOKUP_TABLE name")?;
            }
            let integer = LEGACY_INTEGERS
                .iter()
                .any(|i| data_type.eq_ignore_ascii_case(i));
            if section.eq_ignore_ascii_case("CELL_DATA") && integer && components == 1 {
                let mut v = Vec::new();
                for i in 0..n {
                    v.push(t.value(section, n, format_args!("values of {name}"), i)?);
                }
                m.cell_data.push((name.to_string(), v));
            } else {
                // Skipped, counted only to step over the values.
                let total = n.saturating_mul(components);
                for i in 0..total {
                    t.0.next().ok_or_else(|| {
                        format!("SCALARS {name} needs {total} values but the file ends after {i}")
                    })?;
                }
            }
        }
        // Anything else (other attributes, FIELD, METADATA) is stepped over word by word.
    }
    if let Some(types) = &types {
        if types.len() != m.cells.len() {
            return Err(format!(
                "CELL_TYPES has {} types for {} cells",
                types.len(),
                m.cells.len()
            ));
        }
    }
    if let Some(n) = cell_data_count {
        if n != m.cells.len() {
            return Err(format!(
                "CELL_DATA says {n} cells but CELLS has {}",
                m.cells.len()
            ));
        }
    }
    check_cells(&m, types.as_deref())?;
    Ok(m)
}

/// The attributes of a tag, unescaped.
fn attributes(e: &BytesStart) -> Result<Vec<(String, String)>, String> {
    let tag = String::from_utf8_lossy(e.local_name().as_ref()).into_owned();
    e.attributes()
        .map(|a| {
            let a = a.map_err(|err| format!("bad attribute in <{tag}>: {err}"))?;
            let key = String::from_utf8_lossy(a.key.local_name().as_ref()).into_owned();
            let value = a
                .unescape_value()
                .map_err(|err| format!("bad value of {key} in <{tag}>: {err}"))?;
            Ok((key, value.into_owned()))
        })
        .collect()
}

fn attribute<'a>(attrs: &'a [(String, String)], key: &str) -> Option<&'a str> {
    attrs
        .iter()
        .find(|(k, _)| k == key)
        .map(|(_, v)| v.as_str())
}

/// A count attribute such as `NumberOfPoints`, required.
fn count_attribute(attrs: &[(String, String)], tag: &str, key: &str) -> Result<usize, String> {
    let v = attribute(attrs, key).ok_or_else(|| format!("<{tag}> has no {key}"))?;
    v.trim()
        .parse()
        .map_err(|_| format!("bad {key}=\"{v}\" in <{tag}>"))
}

/// One `DataArray` of the piece: its attributes and the text directly inside it.
struct DataArray<'a> {
    attrs: Vec<(String, String)>,
    text: Cow<'a, str>,
    /// "Points", "Cells" or "CellData".
    parent: &'static str,
    /// The values of a `format="appended"` array, decoded once the appended data is reached.
    binary: Option<Vec<Number>>,
}

impl DataArray<'_> {
    fn name(&self) -> Option<&str> {
        attribute(&self.attrs, "Name")
    }

    /// "DataArray 'offsets'", or "the Points DataArray" when the array has no name.
    fn describe(&self) -> String {
        match self.name() {
            Some(n) => format!("DataArray '{n}'"),
            None => format!("the {} DataArray", self.parent),
        }
    }

    fn components(&self) -> Result<usize, String> {
        match attribute(&self.attrs, "NumberOfComponents") {
            None => Ok(1),
            Some(v) => v
                .trim()
                .parse()
                .map_err(|_| format!("bad NumberOfComponents=\"{v}\" in {}", self.describe())),
        }
    }

    fn is_integer(&self) -> bool {
        let ints = [
            "Int8", "UInt8", "Int16", "UInt16", "Int32", "UInt32", "Int64", "UInt64",
        ];
        attribute(&self.attrs, "type").is_some_and(|t| ints.contains(&t))
    }

    /// The values: `format="ascii"`, or `"appended"` raw data (decoded into
    /// [`DataArray::binary`]); inline `"binary"` (base64) is refused.
    fn values<T: std::str::FromStr + FromNumber>(&self) -> Result<Vec<T>, String> {
        match attribute(&self.attrs, "format") {
            Some("ascii") => numbers(&self.text, &self.describe()),
            Some("appended") => {
                let values = self.binary.as_deref().unwrap_or_default();
                values
                    .iter()
                    .enumerate()
                    .map(|(i, &n)| {
                        T::from_number(n).ok_or_else(|| {
                            format!(
                                "value {i} of {} is not of the kind expected",
                                self.describe()
                            )
                        })
                    })
                    .collect()
            }
            Some(f) => Err(format!(
                "VTU is read with ASCII or appended raw data: {} has format=\"{f}\"",
                self.describe()
            )),
            None => Err(format!(
                "VTU is read with ASCII or appended raw data: {} has no format attribute",
                self.describe()
            )),
        }
    }
}

/// The text of a `DataArray` whose start tag was just read, up to its end tag. Text inside
/// nested elements (VTK's `InformationKey`) is left out.
fn array_text<'a>(r: &mut Reader<&'a [u8]>) -> Result<Cow<'a, str>, String> {
    fn utf8(b: &[u8]) -> Result<&str, String> {
        std::str::from_utf8(b).map_err(|_| "DataArray text is not UTF-8".to_string())
    }
    fn append<'a>(text: &mut Cow<'a, str>, piece: Cow<'a, [u8]>) -> Result<(), String> {
        match piece {
            // Usually the one piece: borrowed, not copied (a blank one before it is dropped).
            Cow::Borrowed(b) if text.trim().is_empty() => *text = Cow::Borrowed(utf8(b)?),
            piece => text.to_mut().push_str(utf8(&piece)?),
        }
        Ok(())
    }
    let mut text = Cow::Borrowed("");
    let mut depth = 0usize;
    loop {
        match r.read_event().map_err(|e| xml_error(r, e))? {
            Event::Start(_) => depth += 1,
            Event::End(_) if depth == 0 => return Ok(text),
            Event::End(_) => depth -= 1,
            Event::Text(t) if depth == 0 => append(&mut text, t.into_inner())?,
            Event::CData(t) if depth == 0 => append(&mut text, t.into_inner())?,
            Event::GeneralRef(g) if depth == 0 => match g.resolve_char_ref() {
                Ok(Some(c)) => text.to_mut().push(c),
                _ => {
                    let name = String::from_utf8_lossy(&g);
                    return Err(format!("unexpected &{name}; in a DataArray"));
                }
            },
            Event::Eof => return Err("the file ends inside a DataArray".into()),
            _ => {}
        }
    }
}

fn xml_error(r: &Reader<&[u8]>, e: quick_xml::Error) -> String {
    format!("bad XML at byte {}: {e}", r.error_position())
}

fn read_vtu(bytes: &[u8]) -> Result<CellMesh, String> {
    let mut r = Reader::from_reader(bytes);
    // Names of the open elements, outermost first.
    let mut open: Vec<String> = Vec::new();
    let mut root_seen = false;
    let mut piece: Option<(usize, usize)> = None;
    let mut arrays: Vec<DataArray> = Vec::new();
    let mut layout = Layout {
        header64: false,
        zlib: false,
    };
    let mut appended: Option<&[u8]> = None;
    loop {
        let (e, empty) = match r.read_event().map_err(|e| xml_error(&r, e))? {
            Event::Start(e) => (e, false),
            Event::Empty(e) => (e, true),
            Event::End(_) => {
                open.pop();
                if open.is_empty() {
                    break; // </VTKFile>
                }
                continue;
            }
            Event::Eof => break,
            _ => continue,
        };
        let tag = String::from_utf8_lossy(e.local_name().as_ref()).into_owned();
        let path: Vec<&str> = open.iter().map(String::as_str).collect();
        match (path.as_slice(), tag.as_str()) {
            ([], "VTKFile") => {
                root_seen = true;
                let attrs = attributes(&e)?;
                layout = Layout {
                    header64: attribute(&attrs, "header_type") == Some("UInt64"),
                    zlib: match attribute(&attrs, "compressor") {
                        None | Some("") => false,
                        Some("vtkZLibDataCompressor") => true,
                        Some(other) => {
                            return Err(format!(
                                "compressor=\"{other}\": only zlib-compressed or plain data is read"
                            ))
                        }
                    },
                };
                match attribute(&attrs, "type") {
                    Some("UnstructuredGrid") => {}
                    Some(other) => {
                        return Err(format!(
                            "not an unstructured grid: VTKFile type=\"{other}\""
                        ))
                    }
                    None => return Err("<VTKFile> has no type".into()),
                }
            }
            ([], other) => {
                return Err(format!(
                    "not a VTK file: neither '# vtk' legacy nor XML with a <VTKFile> root \
                     (the root is <{other}>)"
                ))
            }
            // Raw appended data need not be XML: the arrays are decoded from its bytes.
            (["VTKFile"], "AppendedData") => {
                let attrs = attributes(&e)?;
                if attribute(&attrs, "encoding") != Some("raw") {
                    return Err(format!(
                        "<AppendedData> with encoding=\"{}\": only raw appended data is read",
                        attribute(&attrs, "encoding").unwrap_or("")
                    ));
                }
                let rest = &bytes[(r.buffer_position() as usize).min(bytes.len())..];
                let start = rest
                    .iter()
                    .position(|&b| b == b'_')
                    .ok_or("<AppendedData> has no '_' before its data")?;
                appended = Some(&rest[start + 1..]);
                break;
            }
            (["VTKFile", "UnstructuredGrid"], "Piece") => {
                if piece.is_some() {
                    return Err("only one Piece is read, and this file has several".into());
                }
                let attrs = attributes(&e)?;
                piece = Some((
                    count_attribute(&attrs, "Piece", "NumberOfPoints")?,
                    count_attribute(&attrs, "Piece", "NumberOfCells")?,
                ));
            }
            (["VTKFile", "UnstructuredGrid", "Piece", parent], "DataArray")
                if ["Points", "Cells", "CellData"].contains(parent) =>
            {
                let parent = match *parent {
                    "Points" => "Points",
                    "Cells" => "Cells",
                    _ => "CellData",
                };
                let attrs = attributes(&e)?;
                let text = if empty {
                    Cow::Borrowed("")
                } else {
                    array_text(&mut r)?
                };
                arrays.push(DataArray {
                    attrs,
                    text,
                    parent,
                    binary: None,
                });
                // The end tag was read with the text.
                continue;
            }
            _ => {}
        }
        if !empty {
            open.push(tag);
        }
    }
    if !root_seen {
        return Err("not a VTK file: neither '# vtk' legacy nor XML with a <VTKFile> root".into());
    }
    let (points, cells) = piece.ok_or("no <Piece> in <UnstructuredGrid>")?;
    for a in &mut arrays {
        // Only the arrays `vtu_mesh` reads: real cell data is skipped undecoded.
        let skipped = a.parent == "CellData" && !(a.is_integer() && a.components() == Ok(1));
        if attribute(&a.attrs, "format") != Some("appended") || skipped {
            continue;
        }
        let data = appended.ok_or_else(|| {
            format!(
                "{} is appended, but the file has no <AppendedData>",
                a.describe()
            )
        })?;
        let offset: usize = attribute(&a.attrs, "offset")
            .and_then(|o| o.trim().parse().ok())
            .ok_or_else(|| format!("{} is appended but has no offset", a.describe()))?;
        let ty = attribute(&a.attrs, "type").unwrap_or_default();
        let raw = decode(data, offset, layout).map_err(|e| format!("{}: {e}", a.describe()))?;
        a.binary = Some(vtu_numbers(&raw, ty).map_err(|e| format!("{}: {e}", a.describe()))?);
    }
    vtu_mesh(&arrays, points, cells)
}

/// The one array of `parent` (named `name`, if given), if any.
fn only<'a, 'b>(
    arrays: &'a [DataArray<'b>],
    parent: &str,
    name: Option<&str>,
) -> Result<Option<&'a DataArray<'b>>, String> {
    let mut found = arrays
        .iter()
        .filter(|a| a.parent == parent && (name.is_none() || a.name() == name));
    let first = found.next();
    if let Some(second) = found.next() {
        return Err(format!("two of {} in <{parent}>", second.describe()));
    }
    Ok(first)
}

/// The values of the `Cells` array `name`, which may be missing only when there are no cells.
fn cells_array<T: std::str::FromStr + FromNumber>(
    arrays: &[DataArray],
    name: &str,
    n_cells: usize,
) -> Result<Vec<T>, String> {
    match only(arrays, "Cells", Some(name))? {
        Some(a) => a.values(),
        None if n_cells == 0 => Ok(Vec::new()),
        None => Err(format!("no '{name}' DataArray in <Cells>")),
    }
}

/// The mesh from a piece's arrays, checked against its `NumberOfPoints` and `NumberOfCells`.
fn vtu_mesh(arrays: &[DataArray], n_points: usize, n_cells: usize) -> Result<CellMesh, String> {
    let coords: Vec<f64> = match only(arrays, "Points", None)? {
        Some(a) => {
            let c = a.components()?;
            if c != 3 {
                return Err(format!("{} has {c} components, not 3", a.describe()));
            }
            a.values()?
        }
        None if n_points == 0 => Vec::new(),
        None => return Err("no DataArray in <Points>".into()),
    };
    if Some(coords.len()) != n_points.checked_mul(3) {
        return Err(format!(
            "the Points DataArray has {} values, but NumberOfPoints=\"{n_points}\" needs 3 each",
            coords.len()
        ));
    }
    let connectivity: Vec<usize> = cells_array(arrays, "connectivity", n_cells)?;
    let offsets: Vec<usize> = cells_array(arrays, "offsets", n_cells)?;
    let types: Vec<i64> = cells_array(arrays, "types", n_cells)?;
    for (name, n) in [("offsets", offsets.len()), ("types", types.len())] {
        if n != n_cells {
            return Err(format!(
                "DataArray '{name}' has {n} values, but NumberOfCells=\"{n_cells}\""
            ));
        }
    }
    let mut m = CellMesh {
        points: coords
            .chunks_exact(3)
            .map(|c| DVec3::new(c[0], c[1], c[2]))
            .collect(),
        ..Default::default()
    };
    let mut prev = 0;
    for (i, &o) in offsets.iter().enumerate() {
        if o < prev || o > connectivity.len() {
            return Err(format!(
                "offset {o} of cell {i} is before the previous one or past the {} values of \
                 the connectivity",
                connectivity.len()
            ));
        }
        m.cells.push(connectivity[prev..o].to_vec());
        prev = o;
    }
    if prev != connectivity.len() {
        return Err(format!(
            "the connectivity has {} values, but the offsets end at {prev}",
            connectivity.len()
        ));
    }
    for a in arrays.iter().filter(|a| a.parent == "CellData") {
        if !a.is_integer() || a.components()? != 1 {
            continue;
        }
        let v: Vec<i64> = a.values()?;
        if v.len() != n_cells {
            return Err(format!(
                "{} has {} values, but NumberOfCells=\"{n_cells}\"",
                a.describe(),
                v.len()
            ));
        }
        m.cell_data
            .push((a.name().unwrap_or_default().to_string(), v));
    }
    check_cells(&m, Some(&types))?;
    Ok(m)
}
