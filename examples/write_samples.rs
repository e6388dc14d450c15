//! Write the project's sample cases to `samples/<name>/case.toml` (or under the directory given
//! as the first argument), the STEP wing built through OpenCASCADE to
//! `samples/wing_step/wing_in_box.step`, and the jet's half body to `samples/jet_step/jet.step`: `cargo run --example write_samples [DIR]`.

use std::path::PathBuf;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let root = std::env::args_os()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("samples"));
    for (name, text) in tetrafoil::samples::all() {
        let dir = root.join(name);
        std::fs::create_dir_all(&dir)?;
        let path = dir.join("case.toml");
        std::fs::write(&path, text)?;
        println!("wrote {}", path.display());
    }
    write_step(&root)?;
    write_jet(&root)?;
    Ok(())
}

/// The STEP wing, built through OpenCASCADE (the `tetrafoil-occt` crate, a dev-dependency:
/// the `tetrafoil` binary itself reads STEP through the plugin and builds nothing).
fn write_step(root: &std::path::Path) -> Result<(), Box<dyn std::error::Error>> {
    let path = root.join(tetrafoil::samples::WING_STEP_FILE);
    std::fs::create_dir_all(path.parent().unwrap())?;
    let (lo, hi) = tetrafoil::samples::wing_box();
    let sections = tetrafoil::samples::wing_sections();
    let built = tetrafoil_occt::build::wing_in_box(&sections, lo, hi, &path)?;
    println!(
        "wrote {} (wing volume {:.6}, fluid volume {:.6}, {} faces)",
        path.display(),
        built.wing_volume,
        built.fluid_volume,
        built.faces
    );
    Ok(())
}

/// The jet's half body: its parts lofted and fused through OpenCASCADE, cut at y = 0.
fn write_jet(root: &std::path::Path) -> Result<(), Box<dyn std::error::Error>> {
    let path = root.join(tetrafoil::samples::JET_STEP_FILE);
    std::fs::create_dir_all(path.parent().unwrap())?;
    let parts: Vec<tetrafoil_occt::build::LoftedPart> = tetrafoil::samples::jet_parts()
        .into_iter()
        .map(|p| tetrafoil_occt::build::LoftedPart {
            name: p.name.to_string(),
            sections: (p.sections.iter())
                .map(|s| s.iter().map(|q| q.to_array()).collect())
                .collect(),
            ring: p.ring,
            nose: p.nose.map(|q| q.to_array()),
            tail: p.tail.map(|q| q.to_array()),
        })
        .collect();
    let built = tetrafoil_occt::build::lofted_body(&parts, true, &path)?;
    let case = path.with_file_name("case.toml");
    std::fs::write(&case, tetrafoil::samples::jet_step_case())?;
    println!(
        "wrote {} (half body volume {:.6}, {} faces, {} on the symmetry plane) and {}",
        path.display(),
        built.volume,
        built.faces,
        built.symmetry_faces,
        case.display()
    );
    Ok(())
}
