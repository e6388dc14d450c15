//! Gmsh MSH 4.1 and 2.2 (ASCII).
//!
//! Each boundary marker is a surface entity (tag = marker index + 1) and each region a volume
//! entity (tag = region index + 1); markers (regions) sharing a name share one physical group,
//! since readers of MSH name boundaries and zones by physical group. Physical tags are distinct
//! across dimensions (surfaces 1..S, volumes S+1..): OpenFOAM's `gmshToFoam` looks names up by
//! tag alone, and named the fluid's cell zone after the surface that shared its tag. Nodes are tagged 1..,
//! elements 1.. with boundary faces first. Prisms (type 6), pyramids (7) and boundary quads (3)
//! keep the mesh's node order, which is Gmsh's; MSH 4.1 gives each entity one block per element
//! type. `scripts/check-msh.py` loads the output in Gmsh.

use super::names::{groups, Groups};
use crate::mesh::{Marker, VolumeMesh};
use glam::DVec3;
use std::io::Write;

/// Which MSH version to write.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Version {
    V41,
    V22,
}

/// Elements of one entity: its dimension, tag, physical tag and element indices.
struct Block {
    dim: u8,
    tag: usize,
    physical: usize,
    elements: Vec<usize>,
}

/// One block per entity; physical tags from `first_physical` on.
fn blocks(
    dim: u8,
    of: &[u32],
    entities: &[Marker],
    g: &Groups,
    first_physical: usize,
) -> Vec<Block> {
    let mut b: Vec<Block> = (0..entities.len())
        .map(|e| Block {
            dim,
            tag: e + 1,
            physical: first_physical + g.of[e],
            elements: Vec::new(),
        })
        .collect();
    for (k, &e) in of.iter().enumerate() {
        b[e as usize].elements.push(k);
    }
    b
}

/// The mesh's elements by dimension: boundary faces (dimension 2) and cells (3).
struct Elements<'a> {
    faces: Vec<&'a [u32]>,
    cells: Vec<&'a [u32]>,
}

impl Elements<'_> {
    fn nodes(&self, dim: u8, k: usize) -> &[u32] {
        if dim == 2 {
            self.faces[k]
        } else {
            self.cells[k]
        }
    }
}

/// Gmsh's element type of a linear element of `dim` with `n` nodes.
fn element_type(dim: u8, n: usize) -> u8 {
    match (dim, n) {
        (2, 3) => 2,
        (2, _) => 3,
        (_, 4) => 4,
        (_, 5) => 7,
        _ => 6,
    }
}

pub(crate) fn write(w: &mut dyn Write, m: &VolumeMesh, version: Version) -> std::io::Result<()> {
    let surfaces = groups(&m.markers);
    let volumes = groups(&m.regions);
    let (faces, face_marker): (Vec<&[u32]>, Vec<u32>) = m.boundary_faces().unzip();
    let (cells, cell_region): (Vec<&[u32]>, Vec<u32>) = m.cells().map(|(_, c, r)| (c, r)).unzip();
    let e = Elements { faces, cells };
    let tri = blocks(2, &face_marker, &m.markers, &surfaces, 1);
    let first_volume = surfaces.names.len() + 1;
    let tet = blocks(3, &cell_region, &m.regions, &volumes, first_volume);
    match version {
        Version::V41 => writeln!(w, "$MeshFormat\n4.1 0 8\n$EndMeshFormat")?,
        Version::V22 => writeln!(w, "$MeshFormat\n2.2 0 8\n$EndMeshFormat")?,
    }
    writeln!(w, "$PhysicalNames")?;
    writeln!(w, "{}", surfaces.names.len() + volumes.names.len())?;
    for (dim, g, first) in [(2, &surfaces, 1), (3, &volumes, first_volume)] {
        for (i, name) in g.names.iter().enumerate() {
            writeln!(w, "{dim} {} \"{name}\"", first + i)?;
        }
    }
    writeln!(w, "$EndPhysicalNames")?;
    match version {
        Version::V41 => write_41(w, m, &e, &tri, &tet),
        Version::V22 => write_22(w, m, &e, &tri, &tet),
    }
}

fn write_41(
    w: &mut dyn Write,
    m: &VolumeMesh,
    e: &Elements,
    tri: &[Block],
    tet: &[Block],
) -> std::io::Result<()> {
    writeln!(w, "$Entities")?;
    writeln!(w, "0 0 {} {}", tri.len(), tet.len())?;
    for b in tri.iter().chain(tet) {
        let (lo, hi) = bounds(m, e, b);
        writeln!(
            w,
            "{} {:e} {:e} {:e} {:e} {:e} {:e} 1 {} 0",
            b.tag, lo.x, lo.y, lo.z, hi.x, hi.y, hi.z, b.physical
        )?;
    }
    writeln!(w, "$EndEntities")?;

    // All nodes in one block, on the first volume (or, without volumes, the first surface).
    let n = m.points.len();
    writeln!(w, "$Nodes")?;
    if n == 0 {
        writeln!(w, "0 0 0 0")?;
    } else {
        let host = tet.first().or(tri.first()).ok_or_else(|| {
            std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "MSH: points but neither boundary markers nor regions to attach them to",
            )
        })?;
        writeln!(w, "1 {n} 1 {n}")?;
        writeln!(w, "{} {} 0 {n}", host.dim, host.tag)?;
        for i in 1..=n {
            writeln!(w, "{i}")?;
        }
        for p in &m.points {
            writeln!(w, "{:e} {:e} {:e}", p.x, p.y, p.z)?;
        }
    }
    writeln!(w, "$EndNodes")?;

    // One block per entity and element type, in the order of the elements' tags.
    let mut filled: Vec<(&Block, u8, Vec<usize>)> = Vec::new();
    for b in tri.iter().chain(tet) {
        for kind in [2, 3, 4, 7, 6] {
            let of_kind: Vec<usize> = (b.elements.iter())
                .copied()
                .filter(|&k| element_type(b.dim, e.nodes(b.dim, k).len()) == kind)
                .collect();
            if !of_kind.is_empty() {
                filled.push((b, kind, of_kind));
            }
        }
    }
    let total = e.faces.len() + e.cells.len();
    writeln!(w, "$Elements")?;
    writeln!(w, "{} {total} {} {total}", filled.len(), total.min(1))?;
    let mut tag = 0;
    for (b, kind, elements) in filled {
        writeln!(w, "{} {} {kind} {}", b.dim, b.tag, elements.len())?;
        for k in elements {
            tag += 1;
            write!(w, "{tag}")?;
            for v in e.nodes(b.dim, k) {
                write!(w, " {}", v + 1)?;
            }
            writeln!(w)?;
        }
    }
    writeln!(w, "$EndElements")
}

fn write_22(
    w: &mut dyn Write,
    m: &VolumeMesh,
    e: &Elements,
    tri: &[Block],
    tet: &[Block],
) -> std::io::Result<()> {
    writeln!(w, "$Nodes\n{}", m.points.len())?;
    for (i, p) in m.points.iter().enumerate() {
        writeln!(w, "{} {:e} {:e} {:e}", i + 1, p.x, p.y, p.z)?;
    }
    writeln!(w, "$EndNodes")?;
    writeln!(w, "$Elements\n{}", e.faces.len() + e.cells.len())?;
    let mut tag = 0;
    for b in tri.iter().chain(tet) {
        for &k in &b.elements {
            tag += 1;
            let nodes = e.nodes(b.dim, k);
            let kind = element_type(b.dim, nodes.len());
            write!(w, "{tag} {kind} 2 {} {}", b.physical, b.tag)?;
            for v in nodes {
                write!(w, " {}", v + 1)?;
            }
            writeln!(w)?;
        }
    }
    writeln!(w, "$EndElements")
}

/// Bounding box of an entity's nodes (zero for an empty entity).
fn bounds(m: &VolumeMesh, e: &Elements, b: &Block) -> (DVec3, DVec3) {
    let mut pts = b
        .elements
        .iter()
        .flat_map(|&k| e.nodes(b.dim, k))
        .map(|&v| m.points[v as usize]);
    let Some(first) = pts.next() else {
        return (DVec3::ZERO, DVec3::ZERO);
    };
    pts.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p)))
}
