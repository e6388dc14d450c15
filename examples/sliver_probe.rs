//! Lists the tets of a CAD file's volume mesh whose minimum dihedral angle is below a bound,
//! with what surrounds them: boundary vertices, boundary faces and their minimum angles, and
//! the edge carrying the small angle. For diagnosing slivers the improver cannot remove.
//! Usage: cargo run --release --example sliver_probe -- FILE [DEGREES]
use std::collections::{HashMap, HashSet};
use tetrafoil::case::case_from_cad;
use tetrafoil::mesh::quality::triangle_min_angle;
use tetrafoil::pipeline::mesh_case;
use tetrafoil::volume::VolumeOptions;

fn dihedrals(p: [glam::DVec3; 4]) -> [(f64, usize, usize); 6] {
    let pairs = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];
    pairs.map(|(i, j)| {
        let others: Vec<usize> = (0..4).filter(|&k| k != i && k != j).collect();
        let (k, l) = (others[0], others[1]);
        let e = (p[j] - p[i]).normalize();
        let a = p[k] - p[i];
        let b = p[l] - p[i];
        let a = (a - e * a.dot(e)).normalize();
        let b = (b - e * b.dot(e)).normalize();
        (a.dot(b).clamp(-1.0, 1.0).acos().to_degrees(), i, j)
    })
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let bound: f64 = args.get(2).map_or(1.0, |s| s.parse().unwrap());
    let mut case = case_from_cad(std::path::Path::new(&args[1])).unwrap();
    // CURVATURE=N: that many segments per circle instead of the default.
    if let Some(n) = std::env::var("CURVATURE").ok().and_then(|v| v.parse().ok()) {
        case.controls.curvature_segments = n;
        case.sizing.set_local_limits(&case.model, &case.controls);
    }
    let (mesh, _) = mesh_case(&mut case, VolumeOptions::default()).unwrap();
    let on_boundary: HashSet<u32> = mesh.boundary.iter().flatten().copied().collect();
    let mut faces: HashMap<[u32; 3], usize> = HashMap::new();
    for (k, t) in mesh.boundary.iter().enumerate() {
        let mut s = *t;
        s.sort();
        faces.insert(s, k);
    }
    let mut edges: HashMap<[u32; 2], Vec<usize>> = HashMap::new();
    for (k, t) in mesh.boundary.iter().enumerate() {
        for i in 0..3 {
            let mut e = [t[i], t[(i + 1) % 3]];
            e.sort();
            edges.entry(e).or_default().push(k);
        }
    }
    for (k, t) in mesh.tets.iter().enumerate() {
        let p = mesh.tet_points(k);
        let d = dihedrals(p);
        let (dmin, i, j) = d
            .iter()
            .copied()
            .fold((f64::MAX, 0, 0), |m, x| if x.0 < m.0 { x } else { m });
        if dmin >= bound {
            continue;
        }
        let nb = t.iter().filter(|v| on_boundary.contains(v)).count();
        let mut bf = vec![];
        for skip in 0..4 {
            let mut f: Vec<u32> = (0..4).filter(|&q| q != skip).map(|q| t[q]).collect();
            f.sort();
            if let Some(&b) = faces.get(&[f[0], f[1], f[2]]) {
                let tp = mesh.triangle_points(b);
                bf.push(format!(
                    "tri {b} marker {} minangle {:.2}",
                    mesh.boundary_marker[b],
                    triangle_min_angle(tp[0], tp[1], tp[2])
                ));
            }
        }
        let mut e = [t[i], t[j]];
        e.sort();
        let on_surface_edge = edges.get(&e).map(|v| v.len()).unwrap_or(0);
        let (a, b) = (p[i], p[j]);
        if std::env::var_os("PROBE_POINTS").is_some() {
            println!("   corners {:?}", p);
        }
        println!(
            "tet {k} dmin {dmin:.3} bverts {nb} small-edge ({},{}) len {:.4} surface-edge-uses {on_surface_edge} at {:?}\n   {}",
            t[i],
            t[j],
            (b - a).length(),
            (a + b) * 0.5,
            bf.join("; ")
        );
    }
}
