//! VTK output (XML `.vtu` and legacy `.vtk`, ASCII) of line, triangle and tet cells with
//! integer cell data, and a reader for the same files so `tetrafoil quality` can check them.

use super::write_atomic;
use glam::DVec3;
use std::io::Write;
use std::path::Path;

/// Cells of one kind: 2 (segments), 3 (triangles) or 4 (tets) nodes each.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CellMesh {
    pub points: Vec<DVec3>,
    pub cells: Vec<Vec<usize>>,
    /// Named integer cell data (e.g. "edge", "face", "region").
    pub cell_data: Vec<(String, Vec<i64>)>,
}

fn vtk_type(n: usize) -> u8 {
    match n {
        2 => 3,
        3 => 5,
        4 => 10,
        _ => 7,
    }
}

/// XML `.vtu` or legacy `.vtk`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Flavour {
    Xml,
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
pub fn write_with(
    path: &Path,
    mesh: &CellMesh,
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
    match flavour {
        Flavour::Legacy => write_atomic(path, |w| write_legacy(w, mesh, reals)),
        Flavour::Xml => write_atomic(path, |w| write_vtu(w, mesh, reals)),
    }
}

fn write_vtu(w: &mut dyn Write, m: &CellMesh, reals: &RealData) -> std::io::Result<()> {
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
        let s: Vec<String> = c.iter().map(|i| i.to_string()).collect();
        writeln!(w, "{}", s.join(" "))?;
    }
    writeln!(w, "</DataArray>")?;
    writeln!(
        w,
        r#"<DataArray type="Int64" Name="offsets" format="ascii">"#
    )?;
    let mut off = 0;
    for c in &m.cells {
        off += c.len();
        writeln!(w, "{off}")?;
    }
    writeln!(w, "</DataArray>")?;
    writeln!(w, r#"<DataArray type="UInt8" Name="types" format="ascii">"#)?;
    for c in &m.cells {
        writeln!(w, "{}", vtk_type(c.len()))?;
    }
    writeln!(w, "</DataArray>")?;
    writeln!(w, "</Cells>")?;
    writeln!(w, "<CellData>")?;
    for (name, data) in &m.cell_data {
        writeln!(
            w,
            r#"<DataArray type="Int64" Name="{name}" format="ascii">"#
        )?;
        for d in data {
            writeln!(w, "{d}")?;
        }
        writeln!(w, "</DataArray>")?;
    }
    for (name, data) in reals {
        writeln!(
            w,
            r#"<DataArray type="Float64" Name="{name}" format="ascii">"#
        )?;
        for d in data {
            writeln!(w, "{d:e}")?;
        }
        writeln!(w, "</DataArray>")?;
    }
    writeln!(w, "</CellData>")?;
    writeln!(w, "</Piece></UnstructuredGrid></VTKFile>")
}

fn write_legacy(w: &mut dyn Write, m: &CellMesh, reals: &RealData) -> std::io::Result<()> {
    writeln!(w, "# vtk DataFile Version 3.0")?;
    writeln!(w, "tetrafoil")?;
    writeln!(w, "ASCII")?;
    writeln!(w, "DATASET UNSTRUCTURED_GRID")?;
    writeln!(w, "POINTS {} double", m.points.len())?;
    for p in &m.points {
        writeln!(w, "{:e} {:e} {:e}", p.x, p.y, p.z)?;
    }
    let size: usize = m.cells.iter().map(|c| c.len() + 1).sum();
    writeln!(w, "CELLS {} {size}", m.cells.len())?;
    for c in &m.cells {
        let s: Vec<String> = c.iter().map(|i| i.to_string()).collect();
        writeln!(w, "{} {}", c.len(), s.join(" "))?;
    }
    writeln!(w, "CELL_TYPES {}", m.cells.len())?;
    for c in &m.cells {
        writeln!(w, "{}", vtk_type(c.len()))?;
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

/// Read a `.vtu` or legacy `.vtk` file of the kind [`write`] produces (ASCII).
pub fn read(path: &Path) -> Result<CellMesh, ReadError> {
    let text = std::fs::read_to_string(path).map_err(|source| ReadError::Io {
        path: path.display().to_string(),
        source,
    })?;
    let bad = |message: String| ReadError::Bad {
        path: path.display().to_string(),
        message,
    };
    if text.starts_with("# vtk") {
        read_legacy(&text).map_err(bad)
    } else {
        read_vtu(&text).map_err(bad)
    }
}

fn numbers<T: std::str::FromStr>(s: &str, what: &str) -> Result<Vec<T>, String> {
    s.split_whitespace()
        .map(|x| {
            x.parse::<T>()
                .map_err(|_| format!("bad number '{x}' in {what}"))
        })
        .collect()
}

fn read_legacy(text: &str) -> Result<CellMesh, String> {
    let mut m = CellMesh::default();
    let mut tokens = text.lines().skip(4).flat_map(|l| l.split_whitespace());
    while let Some(key) = tokens.next() {
        match key {
            "POINTS" => {
                let n: usize = tokens
                    .next()
                    .and_then(|x| x.parse().ok())
                    .ok_or("bad POINTS count")?;
                tokens.next();
                for _ in 0..n {
                    let mut c = [0.0; 3];
                    for x in &mut c {
                        *x = tokens
                            .next()
                            .and_then(|x| x.parse().ok())
                            .ok_or("bad point coordinate")?;
                    }
                    m.points.push(DVec3::from_array(c));
                }
            }
            "CELLS" => {
                let n: usize = tokens
                    .next()
                    .and_then(|x| x.parse().ok())
                    .ok_or("bad CELLS count")?;
                tokens.next();
                for _ in 0..n {
                    let k: usize = tokens
                        .next()
                        .and_then(|x| x.parse().ok())
                        .ok_or("bad cell size")?;
                    let mut cell = Vec::with_capacity(k);
                    for _ in 0..k {
                        cell.push(
                            tokens
                                .next()
                                .and_then(|x| x.parse().ok())
                                .ok_or("bad cell node")?,
                        );
                    }
                    m.cells.push(cell);
                }
            }
            _ => {}
        }
    }
    check_cells(&m)?;
    Ok(m)
}

fn data_array<'a>(text: &'a str, name: &str) -> Option<&'a str> {
    let tag = format!(r#"Name="{name}""#);
    let at = text.find(&tag)?;
    let start = at + text[at..].find('>')? + 1;
    let end = start + text[start..].find("</DataArray>")?;
    Some(&text[start..end])
}

fn read_vtu(text: &str) -> Result<CellMesh, String> {
    let points_at = text.find("<Points>").ok_or("no <Points>")?;
    let p_start = points_at + text[points_at..].find('>').ok_or("bad <Points>")? + 1;
    let p_start = p_start + text[p_start..].find('>').ok_or("bad points array")? + 1;
    let p_end = p_start
        + text[p_start..]
            .find("</DataArray>")
            .ok_or("bad points array")?;
    let coords: Vec<f64> = numbers(&text[p_start..p_end], "points")?;
    let conn: Vec<usize> = numbers(
        data_array(text, "connectivity").ok_or("no connectivity")?,
        "connectivity",
    )?;
    let offsets: Vec<usize> = numbers(data_array(text, "offsets").ok_or("no offsets")?, "offsets")?;
    let mut m = CellMesh {
        points: coords
            .chunks_exact(3)
            .map(|c| DVec3::new(c[0], c[1], c[2]))
            .collect(),
        ..Default::default()
    };
    let mut prev = 0;
    for &o in &offsets {
        if o < prev || o > conn.len() {
            return Err(format!("offset {o} out of order or past the connectivity"));
        }
        m.cells.push(conn[prev..o].to_vec());
        prev = o;
    }
    check_cells(&m)?;
    Ok(m)
}

fn check_cells(m: &CellMesh) -> Result<(), String> {
    for (i, c) in m.cells.iter().enumerate() {
        if let Some(&n) = c.iter().find(|&&n| n >= m.points.len()) {
            return Err(format!(
                "cell {i} refers to point {n}, but there are {} points",
                m.points.len()
            ));
        }
    }
    Ok(())
}
