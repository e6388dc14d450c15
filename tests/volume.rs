//! Volume meshing on native models: valid (exact orientation, conforming, volume equal to the
//! enclosed volume), the right regions, cavities left empty, edge lengths following δ.

mod common;

use std::collections::HashMap;
use tetrafoil::case::parse_case;
use tetrafoil::mesh::VolumeMesh;
use tetrafoil::pipeline::mesh_case;
use tetrafoil::volume::{VolumeOptions, VolumeReport};

fn mesh(text: &str, name: &str) -> (VolumeMesh, VolumeReport) {
    let mut case = parse_case(text, name).unwrap();
    mesh_case(&mut case, VolumeOptions::default()).unwrap()
}

fn mean_edge(m: &VolumeMesh) -> f64 {
    let mut sum = 0.0;
    let mut n = 0;
    for t in &m.tets {
        for i in 0..4 {
            for j in i + 1..4 {
                sum += m.points[t[i] as usize].distance(m.points[t[j] as usize]);
                n += 1;
            }
        }
    }
    sum / n as f64
}

#[test]
fn unit_cube_is_valid_and_fills_its_volume() {
    let (m, r) = mesh(&common::unit_cube(0.2), "cube.toml");
    assert!(r.validity.is_valid(), "{:?}", r.validity.defects);
    assert!(
        (r.validity.volume - 1.0).abs() < 1e-12,
        "{}",
        r.validity.volume
    );
    assert!(r.interior.points > 20, "{:?}", r.interior);
    let e = mean_edge(&m);
    assert!((0.15..0.26).contains(&e), "mean edge {e}");
    assert_eq!(m.markers.len(), 6);
    assert!(m.tet_region.iter().all(|&r| r == 0));
    eprintln!("{r:#?}");
}

#[test]
fn cavity_is_left_empty() {
    let (m, r) = mesh(&common::box_with_cavity(0.5), "cavity.toml");
    assert!(r.validity.is_valid(), "{:?}", r.validity.defects);
    // box [0,4]^3 minus [1,2]^3 (see tests/common)
    eprintln!("volume {} markers {}", r.validity.volume, m.markers.len());
    assert!(
        (r.validity.volume - 63.0).abs() < 1e-9,
        "{}",
        r.validity.volume
    );
}

#[test]
fn embedded_sheet_is_conforming_from_both_sides() {
    let (m, r) = mesh(&common::box_with_sheet(0.4), "sheet.toml");
    assert!(r.validity.is_valid(), "{:?}", r.validity.defects);
    assert!((r.validity.volume - 64.0).abs() < 1e-9);
    let sheet = m.markers.iter().position(|k| k.name == "sheet").unwrap() as u32;
    let mut tets_of: HashMap<[u32; 3], usize> = HashMap::new();
    for t in &m.tets {
        for skip in 0..4 {
            let mut k: Vec<u32> = (0..4).filter(|&i| i != skip).map(|i| t[i]).collect();
            k.sort_unstable();
            *tets_of.entry([k[0], k[1], k[2]]).or_default() += 1;
        }
    }
    let mut area = 0.0;
    let mut count = 0;
    for (k, t) in m.boundary.iter().enumerate() {
        if m.boundary_marker[k] != sheet {
            continue;
        }
        let mut key = *t;
        key.sort_unstable();
        assert_eq!(
            tets_of.get(&key),
            Some(&2),
            "sheet triangle {k} needs a tet on each side"
        );
        let [a, b, c] = m.triangle_points(k);
        area += 0.5 * (b - a).cross(c - a).length();
        count += 1;
    }
    assert!(count > 20, "{count} sheet triangles");
    // The warped bilinear sheet is a little larger than its 2 × 2 shadow.
    assert!(area > 4.0 && area < 4.1, "sheet area {area}");
}

#[test]
fn self_intersecting_boundary_is_refused_with_the_face() {
    let case = parse_case(&common::overlapping_boxes(0.25), "tangle.toml");
    let Ok(mut case) = case else {
        // Refused already when loading: also fine, as long as it is an error, not a panic.
        return;
    };
    let err = mesh_case(&mut case, VolumeOptions::default())
        .expect_err("an intersecting boundary must not give a mesh");
    let text = err.to_string();
    assert!(
        text.contains("intersects itself") && text.contains("face "),
        "{text}"
    );
}

#[test]
fn cli_bad_input_exits_non_zero_with_a_message() {
    let dir = std::env::temp_dir().join(format!("tetrafoil-vol-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cases = [
        (
            "tangle.toml",
            common::overlapping_boxes(0.25),
            "intersects itself",
        ),
        // One face missing: an open shell, named by its free edges.
        (
            "open.toml",
            common::unit_cube(0.25).replace("\"f00\", ", ""),
            "edge",
        ),
        (
            "empty.toml",
            common::unit_cube(0.25) + "[[region]]\nname = \"nothing\"\nfaces = []\n",
            "nothing",
        ),
    ];
    for (name, text, needle) in cases {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_tetrafoil"))
            .args(["-q", "mesh"])
            .arg(&path)
            .arg("-o")
            .arg(dir.join("out.su2"))
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{name}: succeeded");
        assert_ne!(out.status.code(), Some(101), "{name}: panicked: {stderr}");
        assert!(stderr.contains(needle), "{name}: {stderr}");
        assert!(!dir.join("out.su2").exists(), "{name}: wrote a mesh");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn two_regions_share_a_conforming_interface() {
    let (m, r) = mesh(&common::two_boxes(0.2), "two.toml");
    assert!(r.validity.is_valid(), "{:?}", r.validity.defects);
    assert_eq!(m.regions.len(), 2);
    let mut volume = [0.0; 2];
    for (k, &reg) in m.tet_region.iter().enumerate() {
        let p = m.tet_points(k);
        volume[reg as usize] += (p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0]) / 6.0;
    }
    assert!(
        (volume[0] - 1.0).abs() < 1e-12 && (volume[1] - 1.0).abs() < 1e-12,
        "{volume:?}"
    );
    // Every triangle of the shared face x = 1 has a tet of each region on its two sides.
    let x1 = m.markers.iter().position(|k| k.name == "x1").unwrap() as u32;
    let mut sides: HashMap<[u32; 3], Vec<u32>> = HashMap::new();
    for (t, &reg) in m.tets.iter().zip(&m.tet_region) {
        for skip in 0..4 {
            let mut k: Vec<u32> = (0..4).filter(|&i| i != skip).map(|i| t[i]).collect();
            k.sort_unstable();
            sides.entry([k[0], k[1], k[2]]).or_default().push(reg);
        }
    }
    let mut shared = 0;
    for (k, t) in m.boundary.iter().enumerate() {
        if m.boundary_marker[k] == x1 {
            let mut key = *t;
            key.sort_unstable();
            let mut regs = sides[&key].clone();
            regs.sort_unstable();
            assert_eq!(regs, vec![0, 1], "interface triangle {k}");
            shared += 1;
        }
    }
    assert!(shared > 20, "{shared} interface triangles");
}

/// An embedded edge (a wire on no face) comes out as a chain of mesh edges: its nodes, on
/// the segment, consecutive ones joined by a tet edge.
#[test]
fn embedded_edge_is_a_chain_of_mesh_edges() {
    let (a, b) = ([0.7, 1.1, 0.9], [3.2, 2.9, 3.1]);
    let (m, r) = mesh(&common::box_with_wire(0.5, a, b), "wire.toml");
    assert!(r.validity.is_valid(), "{:?}", r.validity.defects);
    assert!((r.validity.volume - 64.0).abs() < 1e-9);
    let (a, b) = (glam::DVec3::from_array(a), glam::DVec3::from_array(b));
    let d = b - a;
    // Nodes on the wire, by parameter.
    let mut on: Vec<(f64, u32)> = m
        .points
        .iter()
        .enumerate()
        .filter_map(|(i, p)| {
            let t = (*p - a).dot(d) / d.length_squared();
            let off = (*p - (a + t * d)).length();
            ((-1e-12..=1.0 + 1e-12).contains(&t) && off < 1e-9 * d.length())
                .then_some((t, i as u32))
        })
        .collect();
    on.sort_by(|x, y| x.0.total_cmp(&y.0));
    assert!(on.len() >= 6, "{} nodes on the wire", on.len());
    assert!(on[0].0.abs() < 1e-12 && (on[on.len() - 1].0 - 1.0).abs() < 1e-12);
    let mut edges = std::collections::HashSet::new();
    for t in &m.tets {
        for i in 0..4 {
            for j in 0..4 {
                edges.insert((t[i], t[j]));
            }
        }
    }
    for w in on.windows(2) {
        assert!(
            edges.contains(&(w[0].1, w[1].1)),
            "wire piece {:?}-{:?} is not a mesh edge",
            m.points[w[0].1 as usize],
            m.points[w[1].1 as usize]
        );
    }
    assert_eq!(r.embedded_segments, on.len() - 1);
    assert_eq!(r.embedded_segments_lost, 0);
    eprintln!("wire: {} nodes, recovery {:?}", on.len(), r.recovery);
}
