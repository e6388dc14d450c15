//! Write the project's sample cases to `samples/<name>/case.toml` (or under the directory given
//! as the first argument): `cargo run --example write_samples [DIR]`.

use std::path::PathBuf;

fn main() -> std::io::Result<()> {
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
    Ok(())
}
