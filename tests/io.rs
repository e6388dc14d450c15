//! Solver-format writers: a hand-made cube mesh is written in every format, read back with a
//! small parser per format, and compared exactly (coordinates bit for bit, element vertex
//! order, region and marker names).

mod common;

use glam::DVec3;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use tetrafoil::io::{vtk, write_surface, write_volume, MeshFormat};
use tetrafoil::mesh::quality::{tet_radius_ratio, tet_shape, volume_sign};
use tetrafoil::mesh::{Marker, VolumeMesh};
use tetrafoil::surface::SurfaceMesh;

const FACE_NAMES: [&str; 6] = ["xmin", "xmax", "ymin", "ymax", "wall", "farfield"];

/// The box [1/3, 1/3 + 0.1] × [-2/7, -2/7 + 0.7] × [1e-17, 1.3] (coordinates that do not
/// survive a short decimal) split into the 6 Kuhn tets around its main diagonal; tets 0-2 in
/// region "inner", 3-5 in "outer"; the 12 boundary triangles oriented outwards, one marker
/// per side.
fn cube() -> VolumeMesh {
    let lo = DVec3::new(1.0 / 3.0, -2.0 / 7.0, 1e-17);
    let size = DVec3::new(0.1, 0.7, 1.3);
    let points: Vec<DVec3> = (0..8)
        .map(|i| lo + size * DVec3::new((i & 1) as f64, (i >> 1 & 1) as f64, (i >> 2) as f64))
        .collect();
    let mut tets = Vec::new();
    for axes in [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ] {
        let a = 1u32 << axes[0];
        let b = a | 1 << axes[1];
        let mut t = [0, a, b, 7];
        if volume_sign(t.map(|v| points[v as usize])) < 0.0 {
            t.swap(2, 3);
        }
        tets.push(t);
    }
    // Boundary: tet faces seen once, oriented away from the tet's fourth vertex.
    let mut count: HashMap<[u32; 3], usize> = HashMap::new();
    for t in &tets {
        for skip in 0..4 {
            let mut f: Vec<u32> = (0..4).filter(|&i| i != skip).map(|i| t[i]).collect();
            f.sort();
            *count.entry([f[0], f[1], f[2]]).or_default() += 1;
        }
    }
    let mut boundary = Vec::new();
    let mut boundary_marker = Vec::new();
    for t in &tets {
        for skip in 0..4 {
            let f: Vec<u32> = (0..4).filter(|&i| i != skip).map(|i| t[i]).collect();
            let mut key = f.clone();
            key.sort();
            if count[&[key[0], key[1], key[2]]] != 1 {
                continue;
            }
            let p = |v: u32| points[v as usize];
            let mut tri = [f[0], f[1], f[2]];
            // volume_sign > 0: the fourth vertex is on the normal's side, i.e. inwards.
            if volume_sign([p(tri[0]), p(tri[1]), p(tri[2]), p(t[skip])]) > 0.0 {
                tri.swap(1, 2);
            }
            let [a, b, c] = tri.map(p);
            let centre = lo + 0.5 * size;
            assert!(
                (b - a).cross(c - a).dot(a + b + c - 3.0 * centre) > 0.0,
                "outwards"
            );
            // The side: the axis on which all three corners agree.
            let axis = (0..3)
                .find(|&a| tri.iter().all(|&v| (v >> a & 1) == (tri[0] >> a & 1)))
                .unwrap();
            boundary.push(tri);
            boundary_marker.push((2 * axis + (tri[0] >> axis & 1) as usize) as u32);
        }
    }
    assert_eq!(boundary.len(), 12);
    VolumeMesh {
        points,
        tets,
        tet_region: vec![0, 0, 0, 1, 1, 1],
        boundary,
        boundary_marker,
        markers: FACE_NAMES
            .iter()
            .enumerate()
            .map(|(id, n)| Marker {
                id: 10 + id,
                name: n.to_string(),
            })
            .collect(),
        regions: ["inner", "outer"]
            .iter()
            .enumerate()
            .map(|(id, n)| Marker {
                id,
                name: n.to_string(),
            })
            .collect(),
        ..Default::default()
    }
}

/// What a file says, in the writer-independent form the tests compare.
#[derive(Debug, Default, PartialEq)]
struct Parsed {
    points: Vec<DVec3>,
    tets: Vec<([u32; 4], String)>,
    tris: Vec<([u32; 3], String)>,
}

impl Parsed {
    fn sorted(mut self) -> Self {
        self.tets.sort();
        self.tris.sort();
        self
    }
}

fn expected(m: &VolumeMesh) -> Parsed {
    Parsed {
        points: m.points.clone(),
        tets: m
            .tets
            .iter()
            .zip(&m.tet_region)
            .map(|(t, &r)| (*t, m.regions[r as usize].name.clone()))
            .collect(),
        tris: m
            .boundary
            .iter()
            .zip(&m.boundary_marker)
            .map(|(t, &k)| (*t, m.markers[k as usize].name.clone()))
            .collect(),
    }
    .sorted()
}

/// A fresh empty directory for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("tetrafoil-io-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Write with `write`, check that the directory holds exactly that file (no temporary left
/// behind), return its text.
fn written(name: &str, file: &str, write: impl FnOnce(&Path) -> std::io::Result<()>) -> String {
    let dir = scratch(name);
    let path = dir.join(file);
    write(&path).unwrap();
    let entries: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    assert_eq!(entries, [file], "only the target file remains");
    let text = std::fs::read_to_string(&path).unwrap();
    // TETRAFOIL_IO_KEEP=dir keeps a copy for outside readers (scripts/check-msh.py).
    if let Some(keep) = std::env::var_os("TETRAFOIL_IO_KEEP") {
        std::fs::copy(&path, Path::new(&keep).join(format!("{name}-{file}"))).unwrap();
    }
    std::fs::remove_dir_all(&dir).unwrap();
    text
}

fn num<T: std::str::FromStr>(s: &str) -> T {
    s.parse()
        .unwrap_or_else(|_| panic!("'{s}' is not a number of the expected kind"))
}

fn point(words: &[&str]) -> DVec3 {
    DVec3::new(num(words[0]), num(words[1]), num(words[2]))
}

fn parse_su2(text: &str) -> Parsed {
    let mut p = Parsed::default();
    let mut lines = text.lines();
    let mut region_ranges = Vec::new();
    let mut tag = String::new();
    while let Some(line) = lines.next() {
        let w: Vec<&str> = line.split_whitespace().collect();
        match w.first().copied() {
            // "% region <index> <name>: elements <first> to <last>"
            Some("%") if w.get(1) == Some(&"region") => {
                let name = w[3].trim_end_matches(':').to_string();
                region_ranges.push((num::<usize>(w[5]), num::<usize>(w[7]), name));
            }
            Some("NDIME=") => assert_eq!(w[1], "3"),
            Some("NELEM=") => {
                for i in 0..num(w[1]) {
                    let e: Vec<u32> = lines.next().unwrap().split_whitespace().map(num).collect();
                    assert_eq!((e[0], e.len(), e[5]), (10, 6, i), "tet line with its index");
                    let region = region_ranges
                        .iter()
                        .find(|(a, b, _)| (*a..=*b).contains(&(i as usize)))
                        .map(|r| r.2.clone())
                        .expect("every element in a region range");
                    p.tets.push(([e[1], e[2], e[3], e[4]], region));
                }
            }
            Some("NPOIN=") => {
                for _ in 0..num(w[1]) {
                    let c: Vec<&str> = lines.next().unwrap().split_whitespace().collect();
                    assert_eq!(c.len(), 3);
                    p.points.push(point(&c));
                }
            }
            Some("NMARK=") => assert_eq!(w[1], "6"),
            Some("MARKER_TAG=") => tag = w[1].to_string(),
            Some("MARKER_ELEMS=") => {
                for _ in 0..num(w[1]) {
                    let e: Vec<u32> = lines.next().unwrap().split_whitespace().map(num).collect();
                    assert_eq!((e[0], e.len()), (5, 4));
                    p.tris.push(([e[1], e[2], e[3]], tag.clone()));
                }
            }
            None | Some("%") => {}
            Some(other) => panic!("unexpected SU2 line '{other}'"),
        }
    }
    p.sorted()
}

/// The lines between `$Name` and `$EndName`.
fn section<'a>(text: &'a str, name: &str) -> Vec<&'a str> {
    let start = format!("${name}");
    let end = format!("$End{name}");
    text.lines()
        .skip_while(|l| *l != start)
        .skip(1)
        .take_while(|l| *l != end)
        .collect()
}

/// `(dim, tag) -> name` from `$PhysicalNames`.
fn physical_names(text: &str) -> HashMap<(u32, u32), String> {
    let lines = section(text, "PhysicalNames");
    let n: usize = num(lines[0]);
    assert_eq!(lines.len(), n + 1);
    lines[1..]
        .iter()
        .map(|l| {
            let w: Vec<&str> = l.splitn(3, ' ').collect();
            ((num(w[0]), num(w[1])), w[2].trim_matches('"').to_string())
        })
        .collect()
}

fn parse_msh41(text: &str) -> Parsed {
    assert_eq!(section(text, "MeshFormat"), ["4.1 0 8"]);
    let names = physical_names(text);
    // Entities: (dim, entity tag) -> physical tag.
    let ent = section(text, "Entities");
    let counts: Vec<usize> = ent[0].split_whitespace().map(num).collect();
    assert_eq!(counts, [0, 0, 6, 2]);
    let mut physical = HashMap::new();
    for (i, l) in ent[1..].iter().enumerate() {
        let w: Vec<&str> = l.split_whitespace().collect();
        let dim = if i < counts[2] { 2 } else { 3 };
        assert_eq!(w[7], "1", "one physical tag per entity");
        physical.insert((dim, num::<u32>(w[0])), num::<u32>(w[8]));
    }
    let mut p = Parsed::default();
    let nodes = section(text, "Nodes");
    let head: Vec<usize> = nodes[0].split_whitespace().map(num).collect();
    let mut at = 1;
    let mut coords = HashMap::new();
    for _ in 0..head[0] {
        let n: usize = num(nodes[at].split_whitespace().nth(3).unwrap());
        for k in 0..n {
            let tag: usize = num(nodes[at + 1 + k]);
            let c: Vec<&str> = nodes[at + 1 + n + k].split_whitespace().collect();
            coords.insert(tag, point(&c));
        }
        at += 1 + 2 * n;
    }
    assert_eq!(coords.len(), head[1]);
    p.points = (1..=coords.len()).map(|t| coords[&t]).collect();
    let elements = section(text, "Elements");
    let head: Vec<usize> = elements[0].split_whitespace().map(num).collect();
    let mut at = 1;
    let mut tags = Vec::new();
    for _ in 0..head[0] {
        let w: Vec<u32> = elements[at].split_whitespace().map(num).collect();
        let (dim, entity, kind, n) = (w[0], w[1], w[2], w[3] as usize);
        let name = names[&(dim, physical[&(dim, entity)])].clone();
        for l in &elements[at + 1..at + 1 + n] {
            let e: Vec<u32> = l.split_whitespace().map(num).collect();
            tags.push(e[0]);
            let v: Vec<u32> = e[1..].iter().map(|t| t - 1).collect();
            match kind {
                2 => p.tris.push(([v[0], v[1], v[2]], name.clone())),
                4 => p.tets.push(([v[0], v[1], v[2], v[3]], name.clone())),
                _ => panic!("element type {kind}"),
            }
        }
        at += 1 + n;
    }
    assert_eq!(
        tags,
        (1..=head[1] as u32).collect::<Vec<_>>(),
        "element tags 1.."
    );
    p.sorted()
}

fn parse_msh22(text: &str) -> Parsed {
    assert_eq!(section(text, "MeshFormat"), ["2.2 0 8"]);
    let names = physical_names(text);
    let mut p = Parsed::default();
    let nodes = section(text, "Nodes");
    for (i, l) in nodes[1..].iter().enumerate() {
        let w: Vec<&str> = l.split_whitespace().collect();
        assert_eq!(num::<usize>(w[0]), i + 1);
        p.points.push(point(&w[1..]));
    }
    assert_eq!(p.points.len(), num::<usize>(nodes[0]));
    let elements = section(text, "Elements");
    assert_eq!(elements.len(), num::<usize>(elements[0]) + 1);
    for l in &elements[1..] {
        let e: Vec<u32> = l.split_whitespace().map(num).collect();
        assert_eq!(e[2], 2, "two tags: physical, elementary");
        let v: Vec<u32> = e[5..].iter().map(|t| t - 1).collect();
        match e[1] {
            2 => p.tris.push(([v[0], v[1], v[2]], names[&(2, e[3])].clone())),
            4 => p
                .tets
                .push(([v[0], v[1], v[2], v[3]], names[&(3, e[3])].clone())),
            k => panic!("element type {k}"),
        }
    }
    p.sorted()
}

fn parse_medit(text: &str, m: &VolumeMesh) -> Parsed {
    let mut p = Parsed::default();
    let mut lines = text
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('#'));
    assert_eq!(lines.next(), Some("MeshVersionFormatted 2"));
    assert_eq!(lines.next(), Some("Dimension 3"));
    while let Some(key) = lines.next() {
        let n: usize = if key == "End" {
            0
        } else {
            num(lines.next().unwrap())
        };
        for _ in 0..n {
            let w: Vec<&str> = lines.next().unwrap().split_whitespace().collect();
            let r = |i: usize| num::<u32>(w[i]);
            match key {
                "Vertices" => p.points.push(point(&w)),
                "Triangles" => p.tris.push((
                    [r(0) - 1, r(1) - 1, r(2) - 1],
                    m.markers[r(3) as usize - 1].name.clone(),
                )),
                "Tetrahedra" => p.tets.push((
                    [r(0) - 1, r(1) - 1, r(2) - 1, r(3) - 1],
                    m.regions[r(4) as usize - 1].name.clone(),
                )),
                _ => panic!("unexpected MEDIT keyword {key}"),
            }
        }
        if key == "End" {
            assert!(lines.next().is_none());
        }
    }
    // The comment lines name the references.
    assert!(text.contains("# triangle ref 5: wall"));
    assert!(text.contains("# volume element ref 2: outer"));
    p.sorted()
}

/// STL keeps coordinates, not node ids: map them back through the mesh's points (exact bits).
fn parse_stl(text: &str, points: &[DVec3]) -> Vec<([u32; 3], String)> {
    let id: HashMap<[u64; 3], u32> = points
        .iter()
        .enumerate()
        .map(|(i, p)| (p.to_array().map(f64::to_bits), i as u32))
        .collect();
    let mut tris = Vec::new();
    let mut solid = String::new();
    let mut normal = DVec3::ZERO;
    let mut corners = Vec::new();
    for line in text.lines() {
        let w: Vec<&str> = line.split_whitespace().collect();
        match w[0] {
            "solid" => solid = w[1].to_string(),
            "endsolid" => assert_eq!(w[1], solid),
            "facet" => normal = point(&w[2..]),
            "vertex" => corners.push(point(&w[1..])),
            "endfacet" => {
                let [a, b, c] = [corners[0], corners[1], corners[2]];
                let n = (b - a).cross(c - a).normalize();
                assert!(
                    (n - normal).length() < 1e-15,
                    "facet normal {normal} vs {n}"
                );
                let ids = corners
                    .drain(..)
                    .map(|p| id[&p.to_array().map(f64::to_bits)]);
                let ids: Vec<u32> = ids.collect();
                tris.push(([ids[0], ids[1], ids[2]], solid.clone()));
            }
            "outer" | "endloop" => {}
            other => panic!("unexpected STL line '{other}'"),
        }
    }
    tris.sort();
    tris
}

/// The values of a named `<DataArray>` of a `.vtu`.
fn vtu_array<T: std::str::FromStr>(text: &str, name: &str) -> Vec<T> {
    let at = text.find(&format!(r#"Name="{name}""#)).unwrap();
    let start = at + text[at..].find('>').unwrap() + 1;
    let end = start + text[start..].find("</DataArray>").unwrap();
    text[start..end].split_whitespace().map(num).collect()
}

/// `.vtu` and legacy `.vtk` through the crate's own reader, plus the region data.
fn parse_vtk(path: &Path, regions: &[i64], m: &VolumeMesh) -> Parsed {
    let c = vtk::read(path).unwrap();
    Parsed {
        points: c.points,
        tets: c
            .cells
            .iter()
            .zip(regions)
            .map(|(t, &r)| {
                let t: Vec<u32> = t.iter().map(|&v| v as u32).collect();
                ([t[0], t[1], t[2], t[3]], m.regions[r as usize].name.clone())
            })
            .collect(),
        tris: Vec::new(),
    }
    .sorted()
}

fn volume(format: MeshFormat) -> impl FnOnce(&Path) -> std::io::Result<()> {
    move |path| write_volume(path, &cube(), format)
}

#[test]
fn su2_round_trips() {
    let m = cube();
    let text = written("su2", "cube.su2", volume(MeshFormat::Su2));
    assert!(text.contains("% region 0 inner: elements 0 to 2\n% region 1 outer: elements 3 to 5"));
    assert_eq!(parse_su2(&text), expected(&m));
}

#[test]
fn msh41_round_trips() {
    let m = cube();
    let text = written("msh41", "cube.msh", volume(MeshFormat::Msh41));
    assert_eq!(
        physical_names(&text).len(),
        8,
        "6 boundary + 2 volume groups"
    );
    assert_eq!(physical_names(&text)[&(2, 5)], "wall");
    // Volume groups after the surface groups: a tag names one group in any dimension.
    assert_eq!(physical_names(&text)[&(3, 7)], "inner");
    assert_eq!(parse_msh41(&text), expected(&m));
}

#[test]
fn msh22_round_trips() {
    let m = cube();
    let text = written("msh22", "cube.msh", volume(MeshFormat::Msh22));
    assert_eq!(physical_names(&text)[&(3, 8)], "outer");
    let tags: Vec<u32> = physical_names(&text).keys().map(|k| k.1).collect();
    let mut distinct = tags.clone();
    distinct.sort_unstable();
    distinct.dedup();
    assert_eq!(
        distinct.len(),
        tags.len(),
        "physical tags shared across dimensions"
    );
    assert_eq!(parse_msh22(&text), expected(&m));
}

#[test]
fn medit_round_trips() {
    let m = cube();
    let text = written("medit", "cube.mesh", volume(MeshFormat::Medit));
    assert_eq!(parse_medit(&text, &m), expected(&m));
}

#[test]
fn stl_has_one_solid_per_marker() {
    let m = cube();
    let text = written("stl", "cube.stl", volume(MeshFormat::Stl));
    let solids: Vec<&str> = text.lines().filter(|l| l.starts_with("solid ")).collect();
    assert_eq!(solids.len(), 6);
    assert_eq!(parse_stl(&text, &m.points), expected(&m).tris);
}

#[test]
fn vtu_and_vtk_carry_region_and_quality() {
    let m = cube();
    for (format, file) in [(MeshFormat::Vtu, "cube.vtu"), (MeshFormat::Vtk, "cube.vtk")] {
        let dir = scratch(file);
        let path = dir.join(file);
        write_volume(&path, &m, format).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let (regions, quality, min_dihedral): (Vec<i64>, Vec<f64>, Vec<f64>) =
            if format == MeshFormat::Vtu {
                (
                    vtu_array(&text, "region"),
                    vtu_array(&text, "quality"),
                    vtu_array(&text, "min_dihedral"),
                )
            } else {
                let after = |key: &str| -> Vec<&str> {
                    let at = text.find(key).unwrap();
                    text[at..].lines().skip(2).take(6).collect()
                };
                (
                    after("SCALARS region int").iter().map(|s| num(s)).collect(),
                    after("SCALARS quality double")
                        .iter()
                        .map(|s| num(s))
                        .collect(),
                    after("SCALARS min_dihedral double")
                        .iter()
                        .map(|s| num(s))
                        .collect(),
                )
            };
        assert_eq!(regions, [0, 0, 0, 1, 1, 1]);
        for k in 0..6 {
            // The writer's measures, to the bit; the radius ratio as the report computes it,
            // to rounding.
            let (q, d) = tet_shape(m.tet_points(k));
            assert_eq!((quality[k], min_dihedral[k]), (q, d), "exact round trip");
            assert!((q - tet_radius_ratio(m.tet_points(k))).abs() < 1e-12);
            // A Kuhn tet of a box has a right dihedral or less at some edge.
            assert!(min_dihedral[k] > 0.0 && min_dihedral[k] <= 90.0 + 1e-9);
        }
        assert_eq!(parse_vtk(&path, &regions, &m).points, m.points);
        let mut e = expected(&m);
        e.tris.clear();
        assert_eq!(parse_vtk(&path, &regions, &m), e);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

fn surface() -> (SurfaceMesh, Vec<String>) {
    let m = cube();
    let s = SurfaceMesh {
        points: m.points.clone(),
        triangles: m.boundary.iter().map(|t| t.map(|v| v as usize)).collect(),
        face_of: m.boundary_marker.iter().map(|&k| k as usize).collect(),
        ..Default::default()
    };
    (s, FACE_NAMES.iter().map(|s| s.to_string()).collect())
}

#[test]
fn surface_output() {
    let (s, names) = surface();
    let m = cube();
    let tris = expected(&m).tris;

    let text = written("surf-stl", "s.stl", |p| {
        write_surface(p, &s, &names, MeshFormat::Stl)
    });
    assert_eq!(parse_stl(&text, &s.points), tris);

    let text = written("surf-msh", "s.msh", |p| {
        write_surface(p, &s, &names, MeshFormat::Msh41)
    });
    let names_msh = physical_names(&text);
    assert_eq!(names_msh.len(), 6);
    assert!(names_msh.keys().all(|&(dim, _)| dim == 2));
    let section_nodes = section(&text, "Nodes");
    assert_eq!(section_nodes[1], "2 1 0 8", "nodes on surface entity 1");
    let mut elements: Vec<([u32; 3], String)> = Vec::new();
    let lines = section(&text, "Elements");
    let mut at = 1;
    while at < lines.len() {
        let w: Vec<u32> = lines[at].split_whitespace().map(num).collect();
        assert_eq!((w[0], w[2]), (2, 2));
        for l in &lines[at + 1..at + 1 + w[3] as usize] {
            let e: Vec<u32> = l.split_whitespace().map(num).collect();
            // Entity tag = face id + 1; physical tag the same here (names are distinct).
            elements.push((
                [e[1] - 1, e[2] - 1, e[3] - 1],
                names[w[1] as usize - 1].clone(),
            ));
        }
        at += 1 + w[3] as usize;
    }
    elements.sort();
    assert_eq!(elements, tris);

    let dir = scratch("surf-vtu");
    let path = dir.join("s.vtu");
    write_surface(&path, &s, &names, MeshFormat::Vtu).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let face: Vec<usize> = vtu_array(&text, "face");
    assert_eq!(face, s.face_of);
    let c = vtk::read(&path).unwrap();
    assert_eq!(c.points, s.points);
    assert_eq!(
        c.cells,
        s.triangles.iter().map(|t| t.to_vec()).collect::<Vec<_>>()
    );

    let err = write_surface(&dir.join("s.su2"), &s, &names, MeshFormat::Su2).unwrap_err();
    assert_eq!(err.kind(), std::io::ErrorKind::Unsupported);
    let err = write_surface(&dir.join("s.stl"), &s, &names[..3], MeshFormat::Stl).unwrap_err();
    assert_eq!(
        err.kind(),
        std::io::ErrorKind::InvalidInput,
        "face id without a name"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn missing_directory_is_an_error() {
    let dir = scratch("missing").join("no/such/dir");
    for format in [
        MeshFormat::Su2,
        MeshFormat::Msh41,
        MeshFormat::Msh22,
        MeshFormat::Medit,
        MeshFormat::Vtu,
        MeshFormat::Vtk,
        MeshFormat::Stl,
    ] {
        let path = dir.join(format!("cube.{}", format.extension()));
        let err = write_volume(&path, &cube(), format).unwrap_err();
        assert_eq!(err.kind(), std::io::ErrorKind::NotFound, "{format:?}");
    }
    std::fs::remove_dir_all(scratch("missing")).unwrap();
}

#[test]
fn malformed_mesh_is_an_error() {
    let dir = scratch("malformed");
    let mut m = cube();
    m.tet_region[2] = 7;
    let err = write_volume(&dir.join("a.su2"), &m, MeshFormat::Su2).unwrap_err();
    assert_eq!(err.kind(), std::io::ErrorKind::InvalidInput);
    let mut m = cube();
    m.boundary[0][1] = 99;
    let err = write_volume(&dir.join("a.msh"), &m, MeshFormat::Msh41).unwrap_err();
    assert_eq!(err.kind(), std::io::ErrorKind::InvalidInput);
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        0,
        "nothing written"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn formats_by_name_and_extension() {
    use clap::ValueEnum;
    let by_name = |s: &str| MeshFormat::from_str(s, false).unwrap();
    assert_eq!(by_name("su2"), MeshFormat::Su2);
    assert_eq!(by_name("msh"), MeshFormat::Msh41);
    assert_eq!(by_name("msh22"), MeshFormat::Msh22);
    assert_eq!(by_name("mesh"), MeshFormat::Medit);
    assert_eq!(by_name("vtu"), MeshFormat::Vtu);
    assert_eq!(by_name("vtk"), MeshFormat::Vtk);
    assert_eq!(by_name("stl"), MeshFormat::Stl);
    let ext = |s: &str| MeshFormat::from_path(Path::new(s));
    assert_eq!(ext("a/wing.msh"), Some(MeshFormat::Msh41));
    assert_eq!(ext("wing.SU2"), Some(MeshFormat::Su2));
    assert_eq!(ext("wing.mesh"), Some(MeshFormat::Medit));
    assert_eq!(ext("wing.stl"), Some(MeshFormat::Stl));
    assert_eq!(ext("wing.vtk"), Some(MeshFormat::Vtk));
    assert_eq!(ext("wing.vtu"), Some(MeshFormat::Vtu));
    assert_eq!(ext("wing.obj"), None);
    assert_eq!(ext("wing"), None);
}

#[test]
fn markers_sharing_a_name_form_one_group() {
    let mut m = cube();
    m.markers[1].name = "xmin".into();
    m.markers[5].name = "far field".into();
    let text = written("groups", "g.su2", |p| write_volume(p, &m, MeshFormat::Su2));
    assert!(text.contains("NMARK= 5\n"));
    assert!(text.contains("MARKER_TAG= far_field\n"));
    let xmin = text.find("MARKER_TAG= xmin\nMARKER_ELEMS= 4\n");
    assert!(xmin.is_some(), "both x sides under one tag");
    let text = written("groups-msh", "g.msh", |p| {
        write_volume(p, &m, MeshFormat::Msh41)
    });
    let names = physical_names(&text);
    assert_eq!(names.len(), 7);
    let p = parse_msh41(&text);
    assert_eq!(p.tris.iter().filter(|t| t.1 == "xmin").count(), 4);
}

/// A one-piece ASCII `.vtu` of `cells` (VTK type, nodes) over `points`, written by hand the
/// way other programs write them (named Points array, Int32 connectivity).
fn vtu_file(points: &[[f64; 3]], cells: &[(u8, &[usize])]) -> String {
    let join = |v: Vec<String>| v.join(" ");
    let coords = join(points.iter().flatten().map(|x| x.to_string()).collect());
    let conn = join(
        cells
            .iter()
            .flat_map(|c| c.1)
            .map(|v| v.to_string())
            .collect(),
    );
    let offsets = join(
        cells
            .iter()
            .scan(0, |o, c| {
                *o += c.1.len();
                Some(o.to_string())
            })
            .collect(),
    );
    let types = join(cells.iter().map(|c| c.0.to_string()).collect());
    format!(
        r#"<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">
  <UnstructuredGrid>
    <Piece NumberOfPoints="{}" NumberOfCells="{}">
      <Points>
        <DataArray type="Float32" Name="Points" NumberOfComponents="3" format="ascii">{coords}</DataArray>
      </Points>
      <Cells>
        <DataArray type="Int32" Name="connectivity" format="ascii">{conn}</DataArray>
        <DataArray type="Int32" Name="offsets" format="ascii">{offsets}</DataArray>
        <DataArray type="UInt8" Name="types" format="ascii">{types}</DataArray>
      </Cells>
    </Piece>
  </UnstructuredGrid>
</VTKFile>
"#,
        points.len(),
        cells.len()
    )
}

/// The 6 corners of a unit wedge (a triangle at z = 0 and the same at z = 1).
const WEDGE: [[f64; 3]; 6] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [1.0, 0.0, 1.0],
    [0.0, 1.0, 1.0],
];

/// Write `text` as `file` in a fresh directory and read it back with `vtk::read`.
fn read_text(name: &str, file: &str, text: &[u8]) -> Result<vtk::CellMesh, String> {
    let dir = scratch(name);
    let path = dir.join(file);
    std::fs::write(&path, text).unwrap();
    let r = vtk::read(&path).map_err(|e| e.to_string());
    std::fs::remove_dir_all(&dir).unwrap();
    r
}

/// The message of a read that must fail.
fn read_error(name: &str, file: &str, text: &str) -> String {
    match read_text(name, file, text.as_bytes()) {
        Ok(m) => panic!("{name}: read {} cells, expected an error", m.cells.len()),
        Err(e) => e,
    }
}

#[test]
fn vtu_cells_other_than_lines_triangles_tets_prisms_and_pyramids_are_refused() {
    let polygon = vtu_file(&WEDGE, &[(7, &[0, 1, 2, 3, 4, 5])]);
    let e = read_error("polygon", "polygon.vtu", &polygon);
    assert!(
        e.contains("tetrafoil reads lines, triangles, tetrahedra, wedges (prisms) and pyramids"),
        "{e}"
    );
    assert!(e.contains("cell 0 is a polygon (VTK type 7)"), "{e}");
    // A quad has 4 nodes, like a tet: only its type tells them apart.
    let quad = vtu_file(&WEDGE[..4], &[(9, &[0, 1, 4, 3])]);
    let e = read_error("quad", "quad.vtu", &quad);
    assert!(e.contains("tetrafoil reads lines"), "{e}");
    assert!(e.contains("cell 0 is a quad (VTK type 9)"), "{e}");
    // The cell is named by its index; an unnamed type by its number.
    let mixed = vtu_file(&WEDGE, &[(10, &[0, 1, 2, 3]), (99, &[0, 1, 2, 3])]);
    let e = read_error("mixed", "mixed.vtu", &mixed);
    assert!(e.contains("cell 1 is VTK type 99;"), "{e}");
    // A known type with the wrong node count.
    let short = vtu_file(&WEDGE, &[(5, &[0, 1, 2]), (10, &[0, 1, 2, 3, 4])]);
    let e = read_error("short", "short.vtu", &short);
    assert!(
        e.contains("cell 1 is a tetrahedron (VTK type 10) but has 5 nodes, not 4"),
        "{e}"
    );
    // Lines, triangles, tets, wedges and pyramids together read, and in the file's order.
    let ok = vtu_file(
        &WEDGE,
        &[
            (3, &[0, 1]),
            (5, &[0, 1, 2]),
            (10, &[0, 1, 2, 3]),
            (13, &[0, 1, 2, 3, 4, 5]),
            (14, &[0, 1, 4, 3, 2]),
        ],
    );
    let m = read_text("ok", "ok.vtu", ok.as_bytes()).unwrap();
    assert_eq!(
        m.cells,
        [
            vec![0, 1],
            vec![0, 1, 2],
            vec![0, 1, 2, 3],
            vec![0, 1, 2, 3, 4, 5],
            vec![0, 1, 4, 3, 2]
        ]
    );
    assert_eq!(m.points[5], DVec3::new(0.0, 1.0, 1.0));
}

#[test]
fn legacy_cell_types_are_read() {
    let head = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n\
                POINTS 6 double\n0 0 0 1 0 0 0 1 0 0 0 1 1 0 1 0 1 1\n";
    let wedge = format!("{head}CELLS 1 7\n6 0 1 2 3 4 5\nCELL_TYPES 1\n13\n");
    let m = read_text("legacy-wedge", "w.vtk", wedge.as_bytes()).unwrap();
    assert_eq!(m.cells, [vec![0, 1, 2, 3, 4, 5]]);
    let hex = format!("{head}CELLS 1 9\n8 0 1 2 3 4 5 0 1\nCELL_TYPES 1\n12\n");
    let e = read_error("legacy-hex", "h.vtk", &hex);
    assert!(e.contains("cell 0 is a hexahedron (VTK type 12)"), "{e}");
    let quad = format!("{head}CELLS 2 10\n4 0 1 2 3\n4 0 1 4 3\nCELL_TYPES 2\n10\n9\n");
    let e = read_error("legacy-quad", "q.vtk", &quad);
    assert!(e.contains("cell 1 is a quad (VTK type 9)"), "{e}");
    // Without CELL_TYPES the node count gives the kind, as before the types were read.
    let untyped = format!("{head}CELLS 2 8\n4 0 1 2 3\n2 4 5\n");
    let m = read_text("legacy-untyped", "u.vtk", untyped.as_bytes()).unwrap();
    assert_eq!(m.cells, [vec![0, 1, 2, 3], vec![4, 5]]);
    let seven = format!("{head}CELLS 1 8\n7 0 1 2 3 4 5 0\n");
    let e = read_error("legacy-seven", "f.vtk", &seven);
    assert!(
        e.contains("cell 0 has 7 nodes and the file gives no cell types"),
        "{e}"
    );
    let binary = "# vtk DataFile Version 3.0\nt\nBINARY\nDATASET UNSTRUCTURED_GRID\n";
    let e = read_error("legacy-binary", "b.vtk", binary);
    assert!(e.contains("only ASCII legacy VTK is read"), "{e}");
}

#[test]
fn quality_counts_a_wedge_and_refuses_a_polygon() {
    let dir = scratch("quality-wedge");
    let path = dir.join("wedge.vtu");
    let run = |cells: &[(u8, &[usize])]| {
        std::fs::write(&path, vtu_file(&WEDGE, cells)).unwrap();
        std::process::Command::new(env!("CARGO_BIN_EXE_tetrafoil"))
            .args(["quality", path.to_str().unwrap()])
            .output()
            .unwrap()
    };
    let out = run(&[(13, &[0, 1, 2, 3, 4, 5])]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("prisms 1, pyramids 0"), "{stdout}");
    let out = run(&[(7, &[0, 1, 2, 3, 4, 5])]);
    std::fs::remove_dir_all(&dir).unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success(),
        "quality accepted a polygon: {stderr}"
    );
    assert!(
        stderr.contains("cell 0 is a polygon (VTK type 7)"),
        "{stderr}"
    );
    assert!(out.stdout.is_empty(), "no report for a refused mesh");
}

#[test]
fn counts_past_the_end_of_the_file_are_errors_not_allocations() {
    let head = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n";
    let points = format!("{head}POINTS 3 double\n0 0 0 1 0 0 0 1 0\n");
    let cases = [
        (
            format!("{points}CELLS 1 1000000000001\n1000000000000 0 1 2\n"),
            "CELLS says 1000000000000 nodes of cell 0 but the file ends after 3",
        ),
        (
            format!("{head}POINTS 1000000000000000 double\n0 0 0 1 0 0\n"),
            "POINTS says 1000000000000000 points but the file ends after 2",
        ),
        (
            format!("{points}CELLS 1000000000000000000 4\n3 0 1 2\n3 0 1 2\n"),
            "CELLS says 1000000000000000000 cells but the file ends after 2",
        ),
        (
            format!("{points}CELLS 1 4\n3 0 1 2\nCELL_TYPES 1000000000000000000\n5\n"),
            "CELL_TYPES says 1000000000000000000 cells but the file ends after 1",
        ),
        (
            format!(
                "{points}CELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n5\nCELL_DATA 1000000000000000000\n\
                 SCALARS face int 1\nLOOKUP_TABLE default\n0\n"
            ),
            "CELL_DATA says 1000000000000000000 values of face but the file ends after 1",
        ),
        (
            format!("{points}CELLS 18446744073709551616 4\n"),
            "bad CELLS count '18446744073709551616'",
        ),
    ];
    for (i, (text, message)) in cases.iter().enumerate() {
        let e = read_error(&format!("huge-{i}"), "huge.vtk", text);
        assert!(e.contains(message), "{e}");
    }
    // The same in a VTU: the counts are checked against the arrays, not allocated.
    let tri = vtu_file(&WEDGE[..3], &[(5, &[0, 1, 2])]);
    let huge = tri.replace(
        r#"NumberOfPoints="3""#,
        r#"NumberOfPoints="1000000000000000000""#,
    );
    let e = read_error("huge-vtu", "huge.vtu", &huge);
    assert!(
        e.contains(r#"has 9 values, but NumberOfPoints="1000000000000000000" needs 3 each"#),
        "{e}"
    );
    let huge = tri.replace(
        r#"NumberOfCells="1""#,
        r#"NumberOfCells="1000000000000000000""#,
    );
    let e = read_error("huge-vtu-cells", "huge.vtu", &huge);
    assert!(
        e.contains(r#"DataArray 'offsets' has 1 values, but NumberOfCells="1000000000000000000""#),
        "{e}"
    );
}

#[test]
fn vtu_data_the_reader_cannot_take_is_refused_naming_the_array() {
    let tri = vtu_file(&WEDGE[..3], &[(5, &[0, 1, 2])]);
    let binary = tri.replace(
        r#"Name="connectivity" format="ascii">0 1 2<"#,
        r#"Name="connectivity" format="binary">DAAAAAAAAAABAAAAAgAAAA==<"#,
    );
    assert_ne!(binary, tri);
    let e = read_error("binary-vtu", "b.vtu", &binary);
    assert!(
        e.contains(r#"VTU is read with ASCII or appended raw data: DataArray 'connectivity' has format="binary""#),
        "{e}"
    );
    // Appended raw data whose byte count runs past the file's end.
    let mut appended = tri
        .replace(
            r#"Name="Points" NumberOfComponents="3" format="ascii">0 0 0 1 0 0 0 1 0<"#,
            r#"Name="Points" NumberOfComponents="3" format="appended" offset="0"><"#,
        )
        .replace("</VTKFile>\n", "<AppendedData encoding=\"raw\">_")
        .into_bytes();
    appended.extend([0x80, b'<', 0xff, 0, 1, 2]);
    appended.extend(b"</AppendedData></VTKFile>\n");
    let e = read_text("appended-vtu", "a.vtu", &appended).unwrap_err();
    assert!(
        e.contains("DataArray 'Points'") && e.contains("runs past the end"),
        "{e}"
    );
    let e = read_error(
        "polydata",
        "p.vtu",
        &tri.replace(r#"type="UnstructuredGrid""#, r#"type="PolyData""#),
    );
    assert!(
        e.contains(r#"not an unstructured grid: VTKFile type="PolyData""#),
        "{e}"
    );
    let e = read_error("not-xml", "n.vtu", "<html><body>hello</body></html>");
    assert!(e.contains("not a VTK file"), "{e}");
}

#[test]
fn vtk_read_gives_back_what_write_wrote() {
    let points = cube().points;
    let data =
        |n: usize, name: &str| (name.to_string(), (0..n as i64).map(|k| k * 7 - 3).collect());
    let meshes = [
        vtk::CellMesh {
            points: points.clone(),
            cells: vec![vec![0, 1], vec![1, 3], vec![7, 6]],
            cell_data: vec![data(3, "edge")],
        },
        vtk::CellMesh {
            points: points.clone(),
            cells: vec![vec![0, 1, 3], vec![4, 7, 5]],
            cell_data: vec![data(2, "face"), data(2, "region")],
        },
        vtk::CellMesh {
            points: points.clone(),
            cells: cube()
                .tets
                .iter()
                .map(|t| t.iter().map(|&v| v as usize).collect())
                .collect(),
            cell_data: vec![data(6, "region")],
        },
        vtk::CellMesh::default(),
    ];
    let dir = scratch("vtk-identity");
    for (i, m) in meshes.iter().enumerate() {
        for file in ["m.vtu", "m.vtk"] {
            let path = dir.join(format!("{i}-{file}"));
            vtk::write(&path, m).unwrap();
            assert_eq!(&vtk::read(&path).unwrap(), m, "{i} {file}");
            // Real cell data is written for viewers and skipped by the reader.
            let reals = [("quality".to_string(), vec![0.5; m.cells.len()])];
            let flavour = if file.ends_with("vtu") {
                vtk::Flavour::Xml
            } else {
                vtk::Flavour::Legacy
            };
            vtk::write_with(&path, m, &reals, flavour).unwrap();
            assert_eq!(&vtk::read(&path).unwrap(), m, "{i} {file} with reals");
        }
    }
    // Binary VTU (appended, zlib blocks) reads back the same, reals skipped alike.
    for (i, m) in meshes.iter().enumerate() {
        let path = dir.join(format!("{i}-binary.vtu"));
        let reals = [("quality".to_string(), vec![0.5; m.cells.len()])];
        vtk::write_with(&path, m, &reals, vtk::Flavour::XmlBinary).unwrap();
        assert_eq!(&vtk::read(&path).unwrap(), m, "{i} binary");
    }
    // Names needing XML escapes come back as they were; legacy VTK can't hold spaces.
    let mut m = meshes[1].clone();
    m.cell_data[0].0 = r#"a<b & "c""#.into();
    let path = dir.join("escaped.vtu");
    vtk::write(&path, &m).unwrap();
    assert_eq!(vtk::read(&path).unwrap(), m);
    let err = vtk::write(&dir.join("spaced.vtk"), &m).unwrap_err();
    assert_eq!(err.kind(), std::io::ErrorKind::InvalidInput);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn binary_vtu_opens_in_meshio_with_the_asciis_cells_and_data() {
    let Some(python) = common::readers::readers_python() else {
        return;
    };
    let m = cube();
    let dir = scratch("vtu-meshio");
    let ascii = dir.join("a.vtu");
    let binary = dir.join("b.vtu");
    write_volume(&ascii, &m, MeshFormat::Vtu).unwrap();
    write_volume(&binary, &m, MeshFormat::VtuBinary).unwrap();
    let text = std::fs::read(&binary).unwrap();
    assert!(String::from_utf8_lossy(&text).contains(r#"compressor="vtkZLibDataCompressor""#));
    // What meshio sees of each file: points, tets, and every cell data array's values.
    let script = r#"
import json, sys, meshio
out = []
for path in sys.argv[1:]:
    m = meshio.read(path)
    tets = [c.data.tolist() for c in m.cells if c.type == "tetra"]
    data = {k: [x.tolist() for x in v] for k, v in m.cell_data.items()}
    out.append({"points": m.points.tolist(), "tets": tets, "data": data})
print(json.dumps(out))
"#;
    let run = std::process::Command::new(&python)
        .arg("-c")
        .arg(script)
        .arg(&ascii)
        .arg(&binary)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "meshio failed: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    let seen: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    let (a, b) = (&seen[0], &seen[1]);
    assert_eq!(b["tets"][0].as_array().unwrap().len(), 6, "{b}");
    assert_eq!(a["tets"], b["tets"]);
    assert_eq!(a["data"]["region"], b["data"]["region"]);
    // Binary keeps every bit of the coordinates; ASCII keeps them to the printed digits.
    let points = b["points"].as_array().unwrap();
    for (p, q) in points.iter().zip(&m.points) {
        let p: Vec<f64> = p
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        assert_eq!(p, q.to_array().to_vec());
    }
    for name in ["quality", "min_dihedral"] {
        let (x, y) = (&a["data"][name][0], &b["data"][name][0]);
        for (x, y) in x.as_array().unwrap().iter().zip(y.as_array().unwrap()) {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            // Binary writes them single precision.
            assert!(
                (x - y).abs() <= 1e-6 * x.abs().max(1.0),
                "{name}: {x} against {y}"
            );
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn binary_output_needs_a_vtu_and_reads_back_in_quality() {
    let dir = scratch("cli-binary");
    let case = dir.join("cube.toml");
    std::fs::write(&case, common_cube()).unwrap();
    let run = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_tetrafoil"))
            .args(args)
            .current_dir(&dir)
            .output()
            .unwrap()
    };
    let out = run(&["mesh", "cube.toml", "--binary", "-o", "cube.su2", "-q"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        stderr.contains("--binary applies to .vtu output, and no output is .vtu"),
        "{stderr}"
    );
    let out = run(&["mesh", "cube.toml", "--binary", "-o", "cube.vtu", "-q"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read(dir.join("cube.vtu")).unwrap();
    assert!(String::from_utf8_lossy(&text).contains(r#"format="appended""#));
    let out = run(&["quality", "cube.vtu"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("inverted tets 0"), "{stdout}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A unit cube case (the data file the other CLI tests mesh).
fn common_cube() -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/cube.toml"))
        .unwrap()
}

/// UGRID has no interior faces: a wake's triangle (cells on both sides) is left out of the
/// boundary, and its group out of the `.mapbc`, so FUN3D does not take it for a wall.
#[test]
fn ugrid_leaves_a_wake_out_of_the_boundary() {
    let mesh = common::wake::two_tets_across_a_wake();
    let dir = std::env::temp_dir().join(format!("tf_ugrid_wake_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("wake.ugrid");
    write_volume(&file, &mesh, MeshFormat::Ugrid).unwrap();
    let text = std::fs::read_to_string(&file).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next().unwrap(), "5 6 0 2 0 0 0");
    let rows: Vec<&str> = lines.skip(5).collect();
    // Six outer triangles (the wake's [1 2 3] is not among them), each surface id 1.
    let triangles: Vec<&str> = rows[..6].to_vec();
    assert!(!triangles.contains(&"1 2 3"), "{triangles:?}");
    assert_eq!(rows[6..12], ["1"; 6]);
    assert_eq!(rows[12..], ["1 2 3 4", "1 3 2 5"]);
    let mapbc = std::fs::read_to_string(dir.join("wake.mapbc")).unwrap();
    assert_eq!(mapbc, "1\n1 4000 outside\n");
    std::fs::remove_dir_all(&dir).unwrap();
}
