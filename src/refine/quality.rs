//! How well the refined mesh meets its distributions, measured on the finished mesh: the angles
//! of the tets in the stretched region (centroid within the refined distance of a source), the
//! aspect ratio reached, and the normal spacing of the first layers over the source's wall
//! nodes against the distribution asked for — over all of them, and over those at a junction
//! with another stage's walls (a wing root on a fuselage), where the two stacks meet.

use super::field::StageField;
use crate::mesh::quality::tet_dihedrals;
use crate::mesh::VolumeMesh;
use crate::sizing::SizingField;
use glam::DVec3;
use rayon::prelude::*;
use std::collections::HashSet;

/// Layers whose spacing is compared with the distribution.
pub const LAYERS: usize = 20;

/// Percentiles of a sample.
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct Percentiles {
    pub p10: f64,
    pub p50: f64,
    pub p90: f64,
    pub p99: f64,
    pub max: f64,
}

impl Percentiles {
    pub fn of(mut v: Vec<f64>) -> Self {
        if v.is_empty() {
            return Percentiles::default();
        }
        v.sort_by(f64::total_cmp);
        let at = |q: f64| v[((v.len() - 1) as f64 * q).round() as usize];
        Percentiles {
            p10: at(0.1),
            p50: at(0.5),
            p90: at(0.9),
            p99: at(0.99),
            max: v[v.len() - 1],
        }
    }
}

/// The stretched region's quality for one stage.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct StretchedQuality {
    /// Tets whose centroid lies within the refined distance of a source of the stage.
    pub tets: usize,
    pub max_dihedral: Percentiles,
    pub max_face_angle: Percentiles,
    /// Longest edge over shortest height, over the stretched tets.
    pub aspect_ratio: Percentiles,
    /// Source nodes with a first layer measured.
    pub wall_nodes: usize,
    /// First-layer height over the distribution's `first` of its source, over the wall nodes.
    pub first_layer_ratio: Percentiles,
    /// Median over the wall nodes of (spacing of layer k along the column) / (asked for), for
    /// k = 0..LAYERS while columns reach that far.
    pub layer_ratio_median: Vec<f64>,
    /// Wall nodes within their stack's thickness of another stage's source faces.
    pub junction_nodes: usize,
    /// `first_layer_ratio` over the junction nodes alone.
    pub junction_first_layer_ratio: Percentiles,
}

fn max_face_angle(v: [DVec3; 4]) -> f64 {
    let tri = |a: DVec3, b: DVec3, c: DVec3| {
        let ang = |p: DVec3, q: DVec3, r: DVec3| (q - p).angle_between(r - p).to_degrees();
        ang(a, b, c).max(ang(b, c, a)).max(ang(c, a, b))
    };
    tri(v[1], v[2], v[3])
        .max(tri(v[0], v[2], v[3]))
        .max(tri(v[0], v[1], v[3]))
        .max(tri(v[0], v[1], v[2]))
}

fn aspect(v: [DVec3; 4]) -> f64 {
    let vol6 = (v[1] - v[0]).dot((v[2] - v[0]).cross(v[3] - v[0])).abs();
    let faces = [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]];
    let max_area2 = faces
        .iter()
        .map(|f| (v[f[1]] - v[f[0]]).cross(v[f[2]] - v[f[0]]).length())
        .fold(0.0, f64::max);
    let mut longest: f64 = 0.0;
    for i in 0..4 {
        for j in i + 1..4 {
            longest = longest.max(v[i].distance(v[j]));
        }
    }
    if vol6 == 0.0 {
        return f64::INFINITY;
    }
    // Shortest height = 3V / largest face area = vol6 / (2 · area) · 2 = vol6 / max_area2.
    longest / (vol6 / max_area2)
}

/// Measure `mesh` against the stage's `field`; `wall` are the mesh's nodes lying on the
/// stage's face sources (by boundary marker: `source_faces` are model face ids);
/// `other_walls` are the other stages' source faces, for the junctions.
pub fn stretched_quality(
    mesh: &VolumeMesh,
    field: &StageField,
    sizing: &SizingField,
    source_faces: &HashSet<usize>,
    other_walls: &HashSet<usize>,
) -> StretchedQuality {
    let near: Vec<Vec<super::source::Near>> =
        mesh.points.par_iter().map(|&p| field.near(p)).collect();
    let stretched: Vec<usize> = (0..mesh.tets.len())
        .into_par_iter()
        .filter(|&k| {
            let v = mesh.tet_points(k);
            let c = (v[0] + v[1] + v[2] + v[3]) * 0.25;
            let delta = sizing.spacing(c);
            field.sources.iter().enumerate().any(|(s, src)| {
                let phi = mesh.tets[k]
                    .iter()
                    .map(|&i| near[i as usize][s].phi)
                    .sum::<f64>()
                    * 0.25;
                phi < src.distribution.reach(delta)
            })
        })
        .collect();
    let dih: Vec<f64> = stretched
        .par_iter()
        .map(|&k| {
            tet_dihedrals(mesh.tet_points(k))
                .into_iter()
                .fold(0.0, f64::max)
        })
        .collect();
    let face: Vec<f64> = stretched
        .par_iter()
        .map(|&k| max_face_angle(mesh.tet_points(k)))
        .collect();
    let asp: Vec<f64> = stretched
        .par_iter()
        .map(|&k| aspect(mesh.tet_points(k)))
        .collect();

    // Neighbours by tet edges.
    let mut adj: Vec<Vec<u32>> = vec![Vec::new(); mesh.points.len()];
    for t in &mesh.tets {
        for i in 0..4 {
            for j in 0..4 {
                if i != j && !adj[t[i] as usize].contains(&t[j]) {
                    adj[t[i] as usize].push(t[j]);
                }
            }
        }
    }
    let mut wall = vec![false; mesh.points.len()];
    for (tri, &m) in mesh.boundary.iter().zip(&mesh.boundary_marker) {
        if source_faces.contains(&mesh.markers[m as usize].id) {
            for &v in tri {
                wall[v as usize] = true;
            }
        }
    }
    let other_wall_nodes: Vec<[f64; 3]> = (mesh.boundary.iter().zip(&mesh.boundary_marker))
        .filter(|(_, &m)| other_walls.contains(&mesh.markers[m as usize].id))
        .flat_map(|(tri, _)| tri.map(|v| mesh.points[v as usize].to_array()))
        .collect();
    let other_wall_tree = rstar::RTree::bulk_load(other_wall_nodes);
    let mut first = Vec::new();
    let mut junction_first = Vec::new();
    let mut per_layer: Vec<Vec<f64>> = vec![Vec::new(); LAYERS];
    for w in 0..mesh.points.len() {
        if !wall[w] {
            continue;
        }
        // The source the wall node belongs to: the one it is nearest.
        let Some((s, _)) = near[w]
            .iter()
            .enumerate()
            .min_by(|a, b| a.1.phi.total_cmp(&b.1.phi))
        else {
            continue;
        };
        let d = &field.sources[s].distribution;
        let normal = {
            // The source's normal at the node, on the side of its off-wall neighbours (their
            // mean direction alone leans towards the diagonals a prism split gives the node);
            // that mean where the source has no one normal (an edge).
            let up = adj[w]
                .iter()
                .filter(|&&q| !wall[q as usize])
                .map(|&q| (mesh.points[q as usize] - mesh.points[w]).normalize_or_zero())
                .sum::<DVec3>();
            let n = near[w][s].dir;
            if n == DVec3::ZERO {
                up.normalize_or_zero()
            } else if n.dot(up) >= 0.0 {
                n
            } else {
                -n
            }
        };
        if normal == DVec3::ZERO {
            continue;
        }
        // Walk the column: each step the neighbour farther out nearest the normal line through
        // the wall node (a column is straight; judged by the direction from the last point
        // instead, one step aside sends the walk up a neighbouring column), up to where the
        // layers stop (their spacing reached the local δ).
        let reach = d.reach(sizing.spacing(mesh.points[w]));
        let base = mesh.points[w];
        let off_line = |q: u32| {
            let r = mesh.points[q as usize] - base;
            (r - normal * r.dot(normal)).length()
        };
        let mut at = w;
        for (k, layer) in per_layer.iter_mut().enumerate() {
            let phi_here = near[at][s].phi;
            let next = adj[at]
                .iter()
                .copied()
                .filter(|&q| !wall[q as usize] && near[q as usize][s].phi > phi_here)
                .min_by(|&a, &b| off_line(a).total_cmp(&off_line(b)));
            let Some(q) = next else { break };
            let step = near[q as usize][s].phi - phi_here;
            if k == 0 {
                first.push(step / d.first);
                let p = mesh.points[w].to_array();
                let other = other_wall_tree
                    .nearest_neighbor_iter_with_distance_2(&p)
                    .next();
                if other.is_some_and(|(_, d2)| d2.sqrt() <= reach) {
                    junction_first.push(step / d.first);
                }
            }
            if k + 1 >= d.sites().len() || d.sites()[k + 1] > reach * (1.0 + 1e-9) {
                break;
            }
            layer.push(step / d.layer_spacing(k));
            at = q as usize;
        }
    }
    let layer_ratio_median = per_layer
        .into_iter()
        .take_while(|l| !l.is_empty())
        .map(|l| Percentiles::of(l).p50)
        .collect();
    StretchedQuality {
        tets: stretched.len(),
        max_dihedral: Percentiles::of(dih),
        max_face_angle: Percentiles::of(face),
        aspect_ratio: Percentiles::of(asp),
        wall_nodes: first.len(),
        first_layer_ratio: Percentiles::of(first),
        layer_ratio_median,
        junction_nodes: junction_first.len(),
        junction_first_layer_ratio: Percentiles::of(junction_first),
    }
}
