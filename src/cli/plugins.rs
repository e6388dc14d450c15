//! `tetrafoil plugins`: the geometry plugins found (in search order, the first claiming an
//! extension reads it), their versions and extensions, the built-in OpenCASCADE bridge, and
//! the files that looked like plugins but did not load.

use crate::geometry::plugin::{self, registry};

pub fn run() -> anyhow::Result<()> {
    let r = registry();
    println!("plugin ABI version {}", plugin::ABI_VERSION);
    if cfg!(feature = "occt") {
        println!(
            "built in: OpenCASCADE: {}",
            crate::case::OCCT_EXTENSIONS
                .map(|e| format!(".{e}"))
                .join(" ")
        );
    }
    if r.plugins.is_empty() {
        println!(
            "no plugins found ({} is {}; none beside the executable)",
            plugin::PATH_VARIABLE,
            std::env::var(plugin::PATH_VARIABLE).unwrap_or_else(|_| "not set".into())
        );
    }
    for (p, origin) in &r.plugins {
        println!(
            "{} {}: {} ({}; {})",
            p.name,
            p.version,
            p.extensions
                .iter()
                .map(|e| format!(".{e}"))
                .collect::<Vec<_>>()
                .join(" "),
            p.path.display(),
            origin.describe()
        );
    }
    for (path, origin, why) in &r.failed {
        println!(
            "not loaded: {} ({}): {why}",
            path.display(),
            origin.describe()
        );
    }
    Ok(())
}
