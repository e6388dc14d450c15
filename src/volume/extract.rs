//! From the classified tetrahedralisation to the [`VolumeMesh`] the writers take: the tets of
//! every region on compact node numbers (turned to the positive-volume convention of the
//! solver formats), and the recovered triangles with their face markers, each facing out of
//! the domain where the domain lies on one side only; and each node's place in the stretched
//! layers, when the refinement made some.

use super::boundary::OUTSIDE;
use super::delaunay::Delaunay;
use crate::mesh::{LayerTag, Marker, VolumeMesh};
use crate::model::{FaceId, Model};
use glam::DVec3;
use std::collections::HashMap;

pub fn volume_mesh(
    model: &Model,
    dt: &Delaunay,
    region_of: &[u32],
    triangles: &[[u32; 3]],
    face_of: impl Fn(u32) -> FaceId,
    layers: &[Option<LayerTag>],
) -> VolumeMesh {
    let mut mesh = VolumeMesh {
        regions: (0..model.regions.len())
            .map(|r| Marker {
                id: r,
                name: model.regions[r]
                    .name
                    .clone()
                    .unwrap_or_else(|| format!("region_{r}")),
            })
            .collect(),
        ..Default::default()
    };
    let mut node = vec![u32::MAX; dt.num_points()];
    let triangle_of = super::classify::triangle_index(triangles);
    // Per recovered triangle: its outward orientation seen from a domain tet, and how many
    // domain tets it has (1: a boundary, 2: an interface or embedded face).
    let mut seen: Vec<(u8, [u32; 3])> = vec![(0, [0; 3]); triangles.len()];
    for t in dt.tet_ids() {
        if region_of[t as usize] == OUTSIDE {
            continue;
        }
        let v = dt.tet(t);
        for &x in &v {
            if node[x as usize] == u32::MAX {
                node[x as usize] = mesh.points.len() as u32;
                mesh.points.push(DVec3::from_array(dt.point(x)));
            }
        }
        let n = v.map(|x| node[x as usize]);
        // The kernel's positive tets have face (a, b, c) facing away from d; the formats want
        // (a, b, c) facing towards d.
        mesh.tets.push([n[0], n[2], n[1], n[3]]);
        mesh.tet_region.push(region_of[t as usize]);
        for f in 0..4u8 {
            if !dt.is_constrained(t, f) {
                continue;
            }
            let fv = dt.face_vertices(t, f);
            let mut key = fv;
            key.sort_unstable();
            if let Some(&k) = triangle_of.get(&key) {
                let s = &mut seen[k as usize];
                s.0 += 1;
                s.1 = fv;
            }
        }
    }
    let mut marker_of: HashMap<FaceId, u32> = HashMap::new();
    for (k, tri) in triangles.iter().enumerate() {
        let (count, outward) = seen[k];
        if count == 0 {
            continue; // a face no region touches (e.g. inside a cavity): not part of the mesh
        }
        let corners = if count == 1 { outward } else { *tri };
        let face = face_of(k as u32);
        let next = marker_of.len() as u32;
        let m = *marker_of.entry(face).or_insert_with(|| {
            mesh.markers.push(Marker {
                id: face,
                name: model.face_marker(face),
            });
            next
        });
        mesh.boundary.push(corners.map(|x| node[x as usize]));
        mesh.boundary_marker.push(m);
    }
    if layers.iter().any(Option::is_some) {
        // Kernel point ids become node ids; a column keeps its root's kernel id as its name
        // (the surface mesh's node order, which the tets' storage order does not change).
        mesh.point_layer = vec![None; mesh.points.len()];
        for (x, tag) in layers.iter().enumerate() {
            if let (Some(tag), Some(&n)) = (tag, node.get(x)) {
                if n != u32::MAX {
                    mesh.point_layer[n as usize] = Some(*tag);
                }
            }
        }
    }
    mesh
}
