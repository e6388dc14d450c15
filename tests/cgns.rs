//! The CGNS writer, checked by programs no one here wrote: the CGNS library's own `cgnscheck`
//! finds no error or warning in the hybrid plate mesh, and Gmsh's CGNS reader sees every cell
//! by type, none inverted, each marker's faces under its name, and the cube's volume. Without
//! the library the CLI says what to install and leaves the old file as it was.

mod common;

use common::plate::plate;
use common::readers::{readers_python, tool};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use tetrafoil::io::{write_volume, MeshFormat};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("tetrafoil-cgns-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// What `cgnscheck` says of `file`, after checking it ran to the end and found no error and
/// no warning (level 2 shows every warning but the pedantic ones: coordinates without unit
/// exponents).
fn cgnscheck_passes(cgnscheck: &Path, file: &Path) -> String {
    let run = Command::new(cgnscheck)
        .arg("-w2")
        .arg(file)
        .output()
        .unwrap();
    let said =
        String::from_utf8_lossy(&run.stdout).into_owned() + &String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{said}");
    assert!(said.contains("checking complete"), "{said}");
    for bad in ["ERROR", "error", "WARNING"] {
        assert!(!said.contains(bad), "cgnscheck says {bad}:\n{said}");
    }
    said
}

/// What Gmsh reads from a file: cells per type, inverted cells per type (minSICN ≤ 0), the
/// elements of each named surface entity, and the summed volume of the 3-D elements.
const GMSH: &str = r#"
import json, sys, gmsh
gmsh.initialize(["-noenv"])
gmsh.option.setNumber("General.Terminal", 0)
gmsh.open(sys.argv[1])
counts, inverted, volume = {}, {}, 0.0
for etype in gmsh.model.mesh.getElementTypes():
    name = gmsh.model.mesh.getElementProperties(etype)[0]
    tags, _ = gmsh.model.mesh.getElementsByType(etype)
    counts[name] = len(tags)
    if etype in (4, 6, 7):
        q = gmsh.model.mesh.getElementQualities(tags, "minSICN")
        inverted[name] = int(sum(x <= 0 for x in q))
        volume += float(sum(gmsh.model.mesh.getElementQualities(tags, "volume")))
surfaces = {}
for dim, tag in gmsh.model.getEntities(2):
    _, etags, _ = gmsh.model.mesh.getElements(dim, tag)
    name = gmsh.model.getEntityName(dim, tag)
    surfaces[name] = surfaces.get(name, 0) + sum(len(t) for t in etags)
print(json.dumps({"counts": counts, "inverted": inverted, "volume": volume, "surfaces": surfaces}))
"#;

#[test]
fn cgns_passes_cgnscheck_and_gmsh_reads_every_cell_and_marker() {
    let Some(cgnscheck) = tool(Path::new("/usr/bin/cgnscheck"), "scripts/install-cgns.sh") else {
        return;
    };
    let (mesh, _) = plate();
    assert!(!mesh.prisms.is_empty() && !mesh.pyramids.is_empty());
    assert!(!mesh.boundary_quads.is_empty());
    let dir = scratch("plate");
    let file = dir.join("plate.cgns");
    write_volume(&file, &mesh, MeshFormat::Cgns).unwrap();
    let leftovers: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    assert_eq!(leftovers.len(), 1, "only the file itself: {leftovers:?}");

    let said = cgnscheck_passes(&cgnscheck, &file);
    // Each boundary condition and its family, with the guessed type (the cube: six walls).
    for name in ["xmin", "xmax", "ymin", "ymax", "zmin", "zmax"] {
        assert!(said.contains(&format!("checking BC \"{name}\"")), "{said}");
        assert!(
            said.contains(&format!("checking family \"{name}\"")),
            "{said}"
        );
    }

    let Some(python) = readers_python() else {
        return;
    };
    let run = Command::new(&python)
        .arg("-c")
        .arg(GMSH)
        .arg(&file)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "gmsh: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    let g: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    let count = |t: &str| g["counts"][t].as_u64().unwrap_or(0) as usize;
    assert_eq!(count("Tetrahedron 4"), mesh.tets.len(), "{g}");
    assert_eq!(count("Prism 6"), mesh.prisms.len(), "{g}");
    assert_eq!(count("Pyramid 5"), mesh.pyramids.len(), "{g}");
    assert_eq!(count("Triangle 3"), mesh.boundary.len(), "{g}");
    assert_eq!(count("Quadrilateral 4"), mesh.boundary_quads.len(), "{g}");
    for t in ["Tetrahedron 4", "Prism 6", "Pyramid 5"] {
        assert_eq!(g["inverted"][t].as_u64(), Some(0), "{t}: {g}");
    }
    let volume = g["volume"].as_f64().unwrap();
    assert!(
        (volume - 1.0).abs() < 1e-9,
        "the unit cube's volume: {volume}"
    );
    // Every marker's faces, triangles and quads, under its name.
    let mut expected: HashMap<String, u64> = HashMap::new();
    for (_, k) in mesh.boundary_faces() {
        *expected
            .entry(mesh.markers[k as usize].name.clone())
            .or_default() += 1;
    }
    let seen: HashMap<String, u64> = g["surfaces"]
        .as_object()
        .unwrap()
        .iter()
        .map(|(n, c)| (n.clone(), c.as_u64().unwrap()))
        .collect();
    assert_eq!(seen, expected, "{g}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn without_the_library_cgns_output_says_what_to_install_and_keeps_the_old_file() {
    let dir = scratch("missing");
    let case = dir.join("cube.toml");
    std::fs::write(&case, common::plate::cube_text()).unwrap();
    let out = dir.join("cube.cgns");
    std::fs::write(&out, "the user's earlier mesh").unwrap();
    let run = Command::new(env!("CARGO_BIN_EXE_tetrafoil"))
        .env("TETRAFOIL_CGNS_LIB", dir.join("no-such-libcgns.so"))
        .args(["mesh", case.to_str().unwrap(), "-q", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(!run.status.success(), "{stderr}");
    assert!(
        stderr.contains("CGNS output needs the CGNS library")
            && stderr.contains("libcgns-dev")
            && stderr.contains("no-such-libcgns.so"),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(
        std::fs::read_to_string(&out).unwrap(),
        "the user's earlier mesh"
    );
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        2,
        "no temporary left"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Two tets on either side of a wake: the wake's triangle is written (its section is in the
/// file) but gets no boundary condition, which would make it a wall; cgnscheck finds
/// nothing to say.
#[test]
fn a_wake_has_its_faces_but_no_boundary_condition() {
    let Some(cgnscheck) = tool(Path::new("/usr/bin/cgnscheck"), "scripts/install-cgns.sh") else {
        return;
    };
    let mesh = common::wake::two_tets_across_a_wake();
    let dir = scratch("wake");
    let file = dir.join("wake.cgns");
    write_volume(&file, &mesh, MeshFormat::Cgns).unwrap();
    let said = cgnscheck_passes(&cgnscheck, &file);
    assert!(said.contains("checking BC \"outside\""), "{said}");
    assert!(!said.contains("checking BC \"wake\""), "{said}");
    assert!(said.contains("element set \"wake\""), "{said}");
    std::fs::remove_dir_all(&dir).unwrap();
}
