//! Gmsh MSH 4.1 and 2.2 (ASCII).
//!
//! Each boundary marker is a surface entity (tag = marker index + 1) and each region a volume
//! entity (tag = region index + 1); markers (regions) sharing a name share one physical group,
//! since readers of MSH name boundaries and zones by physical group. Physical tags are distinct
//! across dimensions (surfaces 1..S, volumes S+1..): OpenFOAM's `gmshToFoam` looks names up by
//! tag alone, and named the fluid's cell zone after the surface that shared its tag. Nodes are tagged 1..,
//! elements 1.. with triangles first. `scripts/check-msh.py` loads the output in Gmsh.

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

pub(crate) fn write(w: &mut dyn Write, m: &VolumeMesh, version: Version) -> std::io::Result<()> {
    let surfaces = groups(&m.markers);
    let volumes = groups(&m.regions);
    let tri = blocks(2, &m.boundary_marker, &m.markers, &surfaces, 1);
    let first_volume = surfaces.names.len() + 1;
    let tet = blocks(3, &m.tet_region, &m.regions, &volumes, first_volume);
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
        Version::V41 => write_41(w, m, &tri, &tet),
        Version::V22 => write_22(w, m, &tri, &tet),
    }
}

fn write_41(
    w: &mut dyn Write,
    m: &VolumeMesh,
    tri: &[Block],
    tet: &[Block],
) -> std::io::Result<()> {
    writeln!(w, "$Entities")?;
    writeln!(w, "0 0 {} {}", tri.len(), tet.len())?;
    for b in tri.iter().chain(tet) {
        let (lo, hi) = bounds(m, b);
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

    let filled: Vec<&Block> = tri
        .iter()
        .chain(tet)
        .filter(|b| !b.elements.is_empty())
        .collect();
    let total = m.boundary.len() + m.tets.len();
    writeln!(w, "$Elements")?;
    writeln!(w, "{} {total} {} {total}", filled.len(), total.min(1))?;
    let mut tag = 0;
    for b in filled {
        let kind = if b.dim == 2 { 2 } else { 4 };
        writeln!(w, "{} {} {kind} {}", b.dim, b.tag, b.elements.len())?;
        for &k in &b.elements {
            tag += 1;
            write!(w, "{tag}")?;
            for v in nodes(m, b.dim, k) {
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
    tri: &[Block],
    tet: &[Block],
) -> std::io::Result<()> {
    writeln!(w, "$Nodes\n{}", m.points.len())?;
    for (i, p) in m.points.iter().enumerate() {
        writeln!(w, "{} {:e} {:e} {:e}", i + 1, p.x, p.y, p.z)?;
    }
    writeln!(w, "$EndNodes")?;
    writeln!(w, "$Elements\n{}", m.boundary.len() + m.tets.len())?;
    let mut tag = 0;
    for b in tri.iter().chain(tet) {
        let kind = if b.dim == 2 { 2 } else { 4 };
        for &k in &b.elements {
            tag += 1;
            write!(w, "{tag} {kind} 2 {} {}", b.physical, b.tag)?;
            for v in nodes(m, b.dim, k) {
                write!(w, " {}", v + 1)?;
            }
            writeln!(w)?;
        }
    }
    writeln!(w, "$EndElements")
}

fn nodes(m: &VolumeMesh, dim: u8, k: usize) -> &[u32] {
    if dim == 2 {
        &m.boundary[k]
    } else {
        &m.tets[k]
    }
}

/// Bounding box of an entity's nodes (zero for an empty entity).
fn bounds(m: &VolumeMesh, b: &Block) -> (DVec3, DVec3) {
    let mut pts = b
        .elements
        .iter()
        .flat_map(|&k| nodes(m, b.dim, k))
        .map(|&v| m.points[v as usize]);
    let Some(first) = pts.next() else {
        return (DVec3::ZERO, DVec3::ZERO);
    };
    pts.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p)))
}
