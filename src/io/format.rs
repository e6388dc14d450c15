//! Output formats by name or extension, and the two entry points the CLI calls:
//! [`write_volume`] and [`write_surface`].

use super::{cgns, gmsh, medit, stl, su2, ugrid, vtk, write_atomic};
use crate::mesh::quality::tet_shape;
use crate::mesh::{CellKind, Marker, VolumeMesh};
use crate::surface::SurfaceMesh;
use rayon::prelude::*;
use std::io::{Error, ErrorKind};
use std::path::Path;

/// A mesh file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, clap::ValueEnum)]
pub enum MeshFormat {
    /// SU2 native `.su2`.
    #[value(name = "su2")]
    Su2,
    /// Gmsh MSH 4.1 `.msh`.
    #[value(name = "msh")]
    Msh41,
    /// Gmsh MSH 2.2 `.msh` (for older readers, e.g. OpenFOAM's gmshToFoam).
    #[value(name = "msh22")]
    Msh22,
    /// MEDIT / INRIA `.mesh`.
    #[value(name = "mesh")]
    Medit,
    /// VTK XML `.vtu`.
    #[value(name = "vtu")]
    Vtu,
    /// VTK XML `.vtu`, binary: appended raw data in zlib-compressed blocks (`--binary`).
    #[value(name = "vtu-binary")]
    VtuBinary,
    /// Legacy VTK `.vtk`.
    #[value(name = "vtk")]
    Vtk,
    /// ASCII STL of the boundary, one solid per marker.
    #[value(name = "stl")]
    Stl,
    /// AFLR3/FUN3D UGRID, ASCII `.ugrid`, with a `.mapbc` beside it.
    #[value(name = "ugrid")]
    Ugrid,
    /// UGRID binary, little-endian `.lb8.ugrid`, with a `.mapbc`.
    #[value(name = "lb8.ugrid")]
    UgridLb8,
    /// UGRID binary, big-endian `.b8.ugrid`, with a `.mapbc`.
    #[value(name = "b8.ugrid")]
    UgridB8,
    /// CGNS `.cgns` (HDF5), written through the CGNS library (loaded at run time).
    #[value(name = "cgns")]
    Cgns,
}

impl MeshFormat {
    /// The format a file name asks for (`.msh` is MSH 4.1); `None` for an unknown extension.
    pub fn from_path(path: &Path) -> Option<Self> {
        let name = path.file_name()?.to_str()?.to_ascii_lowercase();
        for (suffix, format) in [
            (".lb8.ugrid", Self::UgridLb8),
            (".b8.ugrid", Self::UgridB8),
            (".ugrid", Self::Ugrid),
        ] {
            if name.ends_with(suffix) {
                return Some(format);
            }
        }
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        Some(match ext.as_str() {
            "su2" => Self::Su2,
            "msh" => Self::Msh41,
            "mesh" => Self::Medit,
            "vtu" => Self::Vtu,
            "vtk" => Self::Vtk,
            "stl" => Self::Stl,
            "cgns" => Self::Cgns,
            _ => return None,
        })
    }

    /// The usual file extension (without the dot).
    pub fn extension(self) -> &'static str {
        match self {
            Self::Su2 => "su2",
            Self::Msh41 | Self::Msh22 => "msh",
            Self::Medit => "mesh",
            Self::Vtu | Self::VtuBinary => "vtu",
            Self::Vtk => "vtk",
            Self::Stl => "stl",
            Self::Ugrid => "ugrid",
            Self::UgridLb8 => "lb8.ugrid",
            Self::UgridB8 => "b8.ugrid",
            Self::Cgns => "cgns",
        }
    }
}

impl MeshFormat {
    /// Whether the format writes a `.mapbc` beside the mesh (UGRID's three encodings).
    pub fn has_mapbc(self) -> bool {
        matches!(
            self,
            MeshFormat::Ugrid | MeshFormat::UgridLb8 | MeshFormat::UgridB8
        )
    }
}

/// The `.mapbc` beside a UGRID file: `wing.lb8.ugrid` → `wing.mapbc`.
pub fn mapbc_path(path: &Path) -> std::path::PathBuf {
    let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("mesh");
    let lower = name.to_ascii_lowercase();
    let stem = [".lb8.ugrid", ".b8.ugrid", ".ugrid"]
        .iter()
        .find(|s| lower.ends_with(*s))
        .map_or(name, |s| &name[..name.len() - s.len()]);
    path.with_file_name(format!("{stem}.mapbc"))
}

fn invalid(message: String) -> Error {
    Error::new(ErrorKind::InvalidInput, message)
}

/// The writers index without checks; a malformed mesh is an error here, not a panic there.
fn check(m: &VolumeMesh) -> std::io::Result<()> {
    if m.tet_region.len() != m.tets.len() {
        return Err(invalid(format!(
            "{} tets but {} region ids",
            m.tets.len(),
            m.tet_region.len()
        )));
    }
    if m.boundary_marker.len() != m.boundary.len() {
        return Err(invalid(format!(
            "{} boundary triangles but {} markers ids",
            m.boundary.len(),
            m.boundary_marker.len()
        )));
    }
    if m.prism_region.len() != m.prisms.len()
        || m.pyramid_region.len() != m.pyramids.len()
        || m.quad_marker.len() != m.boundary_quads.len()
    {
        return Err(invalid(format!(
            "{} prisms, {} pyramids and {} boundary quads but {}, {} and {} region or marker ids",
            m.prisms.len(),
            m.pyramids.len(),
            m.boundary_quads.len(),
            m.prism_region.len(),
            m.pyramid_region.len(),
            m.quad_marker.len()
        )));
    }
    let n = m.points.len();
    let cells = m.cells().flat_map(|(_, c, _)| c.iter());
    let vertices = cells.chain(m.boundary_faces().flat_map(|(f, _)| f.iter()));
    if let Some(v) = vertices.copied().find(|&v| v as usize >= n) {
        return Err(invalid(format!("vertex {v} referenced, but {n} points")));
    }
    if let Some(r) = m
        .cells()
        .map(|(_, _, r)| r)
        .find(|&r| r as usize >= m.regions.len())
    {
        return Err(invalid(format!(
            "region id {r}, but {} regions",
            m.regions.len()
        )));
    }
    if let Some(k) = m
        .boundary_faces()
        .map(|(_, k)| k)
        .find(|&k| k as usize >= m.markers.len())
    {
        return Err(invalid(format!(
            "marker id {k}, but {} markers",
            m.markers.len()
        )));
    }
    Ok(())
}

/// Write the volume mesh `m` to `path` in `format` (atomically). STL writes only the boundary.
pub fn write_volume(path: &Path, m: &VolumeMesh, format: MeshFormat) -> std::io::Result<()> {
    check(m)?;
    match format {
        MeshFormat::Su2 => write_atomic(path, |w| su2::write(w, m)),
        MeshFormat::Msh41 => write_atomic(path, |w| gmsh::write(w, m, gmsh::Version::V41)),
        MeshFormat::Msh22 => write_atomic(path, |w| gmsh::write(w, m, gmsh::Version::V22)),
        MeshFormat::Medit => write_atomic(path, |w| medit::write(w, m)),
        MeshFormat::Stl => write_atomic(path, |w| stl::write(w, m)),
        MeshFormat::Cgns => cgns::write(path, m),
        MeshFormat::Vtu => write_volume_vtk(path, m, vtk::Flavour::Xml),
        MeshFormat::VtuBinary => write_volume_vtk(path, m, vtk::Flavour::XmlBinary),
        MeshFormat::Vtk => write_volume_vtk(path, m, vtk::Flavour::Legacy),
        MeshFormat::Ugrid | MeshFormat::UgridLb8 | MeshFormat::UgridB8 => {
            let encoding = match format {
                MeshFormat::Ugrid => ugrid::Encoding::Ascii,
                MeshFormat::UgridLb8 => ugrid::Encoding::LittleEndian,
                _ => ugrid::Encoding::BigEndian,
            };
            let listed = ugrid::listed(m);
            write_atomic(path, |w| ugrid::write(w, m, &listed, encoding))?;
            write_atomic(&mapbc_path(path), |w| ugrid::write_mapbc(w, m, &listed))
        }
    }
}

/// Cells (tets, pyramids, prisms in VTK's order) with cell data `region` (index into
/// `m.regions`), `quality` (radius ratio) and `min_dihedral` (degrees), for looking at the mesh
/// in ParaView; a prism's or pyramid's measures are the worst of its first split's tets.
fn write_volume_vtk(path: &Path, m: &VolumeMesh, flavour: vtk::Flavour) -> std::io::Result<()> {
    let all: Vec<(CellKind, &[u32], u32)> = m.cells().collect();
    let cells = vtk::CellMesh {
        points: m.points.clone(),
        cells: all
            .par_iter()
            .map(|&(kind, c, _)| super::cells::vtk_order(kind, c))
            .collect(),
        cell_data: vec![(
            "region".into(),
            all.iter().map(|&(_, _, r)| r as i64).collect(),
        )],
    };
    // Both measures in one pass; one `acos` per tet (of the largest cosine), not six.
    let (quality, min_dihedral): (Vec<f64>, Vec<f64>) = all
        .par_iter()
        .map(|&(kind, c, _)| {
            if let [a, b, c, d] = *c {
                return tet_shape([a, b, c, d].map(|v| m.points[v as usize]));
            }
            let mut worst = (f64::INFINITY, f64::INFINITY);
            for t in super::cells::split_tets(kind, c) {
                let (quality, min_dihedral) = tet_shape(t.map(|v| m.points[v as usize]));
                worst.0 = worst.0.min(quality);
                worst.1 = worst.1.min(min_dihedral);
            }
            worst
        })
        .unzip();
    let reals = [
        ("quality".to_string(), quality),
        ("min_dihedral".to_string(), min_dihedral),
    ];
    vtk::write_with(path, &cells, &reals, flavour)
}

/// Write a surface mesh alone, one marker per face (`face_names[f]` is face `f`'s marker, e.g.
/// `Model::face_marker(f)`): STL (one solid per name), VTU/VTK (cell data `face`), MSH 4.1 and
/// 2.2 (one physical surface per name) and MEDIT (triangle ref = face id + 1). SU2 needs a
/// volume and is refused with `ErrorKind::Unsupported`.
pub fn write_surface(
    path: &Path,
    s: &SurfaceMesh,
    face_names: &[String],
    format: MeshFormat,
) -> std::io::Result<()> {
    if s.face_of.len() != s.triangles.len() {
        return Err(invalid(format!(
            "{} triangles but {} face ids",
            s.triangles.len(),
            s.face_of.len()
        )));
    }
    if let Some(f) = s.face_of.iter().find(|&&f| f >= face_names.len()) {
        return Err(invalid(format!(
            "face id {f}, but {} face names",
            face_names.len()
        )));
    }
    match format {
        MeshFormat::Su2 => Err(Error::new(
            ErrorKind::Unsupported,
            "SU2 output needs a volume mesh; write the surface as stl, vtu, msh or mesh",
        )),
        MeshFormat::Vtu | MeshFormat::VtuBinary | MeshFormat::Vtk => {
            let flavour = match format {
                MeshFormat::Vtu => vtk::Flavour::Xml,
                MeshFormat::VtuBinary => vtk::Flavour::XmlBinary,
                _ => vtk::Flavour::Legacy,
            };
            let cells = vtk::CellMesh {
                points: s.points.clone(),
                cells: s.triangles.iter().map(|t| t.to_vec()).collect(),
                cell_data: vec![("face".into(), s.face_of.iter().map(|&f| f as i64).collect())],
            };
            vtk::write_with(path, &cells, &[], flavour)
        }
        _ => write_volume(path, &surface_as_volume(s, face_names)?, format),
    }
}

/// A tet-less [`VolumeMesh`] whose boundary is the surface mesh, marker `f` being face `f`.
fn surface_as_volume(s: &SurfaceMesh, face_names: &[String]) -> std::io::Result<VolumeMesh> {
    let id = |v: usize| u32::try_from(v).map_err(|_| invalid(format!("node id {v} over u32")));
    let boundary = s
        .triangles
        .iter()
        .map(|t| Ok([id(t[0])?, id(t[1])?, id(t[2])?]))
        .collect::<std::io::Result<_>>()?;
    let boundary_marker = s
        .face_of
        .iter()
        .map(|&f| id(f))
        .collect::<std::io::Result<_>>()?;
    Ok(VolumeMesh {
        points: s.points.clone(),
        boundary,
        boundary_marker,
        markers: face_names
            .iter()
            .enumerate()
            .map(|(id, name)| Marker {
                id,
                name: name.clone(),
            })
            .collect(),
        ..Default::default()
    })
}
