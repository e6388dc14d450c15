//! The first layer from a y⁺ target (`yplus`, `reynolds`, `chord` in `[[refine.source]]`, or
//! `--yplus --reynolds --chord`): the flat-plate estimate reaches the distribution, and a
//! target missing its Reynolds number or given beside `first` is refused naming the key and
//! its line.

mod common;

use common::plate::cube_text;
use std::process::Command;
use tetrafoil::case::parse_case;

fn stage(keys: &str) -> String {
    format!(
        "{}\n[[refine]]\n[[refine.source]]\nfaces = [\"zmin\"]\n{keys}growth = 1.2\n",
        cube_text()
    )
}

#[test]
fn a_y_plus_target_gives_the_flat_plate_first_layer() {
    let text = stage("yplus = 30\nreynolds = 1e6\nchord = 1\n");
    let case = parse_case(&text, "yplus.toml").expect("loads");
    let source = &case.refinement.stages[0].sources[0];
    // Cf = 0.026 / 1e6^(1/7) = 0.00361; first = 30 / (1e6 √(Cf/2)) = 7.06e-4.
    let cf = 0.026 / 1e6f64.powf(1.0 / 7.0);
    let first = 30.0 / (1e6 * (cf / 2.0).sqrt());
    assert!(
        (source.distribution.first - first).abs() < 1e-15,
        "{}",
        source.distribution.first
    );
    assert!((first - 7.06e-4).abs() < 1e-6, "{first}");
    assert!(source.label.contains("from y+ 30") && source.label.contains("flat plate"));
}

#[test]
fn incomplete_or_doubled_targets_name_the_key_and_line() {
    let err = |text: &str| match parse_case(text, "v.toml") {
        Ok(_) => panic!("loaded:\n{text}"),
        Err(e) => e.to_string(),
    };
    let line_of =
        |text: &str, key: &str| text.lines().position(|l| l.starts_with(key)).unwrap() + 1;
    let text = stage("yplus = 1\n");
    let e = err(&text);
    assert!(
        e.contains(&format!("v.toml:{}", line_of(&text, "yplus")))
            && e.contains("refine.source.yplus")
            && e.contains("needs reynolds"),
        "{e}"
    );
    let text = stage("first = 0.01\nyplus = 1\nreynolds = 1e6\nchord = 1\n");
    let e = err(&text);
    assert!(e.contains("not both"), "{e}");
    let text = stage("first = 0.01\nreynolds = 1e6\n");
    let e = err(&text);
    assert!(
        e.contains("refine.source.reynolds") && e.contains("goes with yplus"),
        "{e}"
    );
    let text = stage("yplus = 1\nreynolds = -5\nchord = 1\n");
    let e = err(&text);
    assert!(
        e.contains(&format!("v.toml:{}", line_of(&text, "reynolds")))
            && e.contains("must be a positive number"),
        "{e}"
    );
    let text = stage("growth_typo = 1\n");
    let e = err(&text);
    assert!(e.contains("growth_typo"), "{e}");
    // The command line says the same.
    let dir = std::env::temp_dir().join(format!("tetrafoil-viscous-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let case = dir.join("cube.toml");
    std::fs::write(&case, cube_text()).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_tetrafoil"))
        .args(["mesh", case.to_str().unwrap(), "-q", "-o"])
        .arg(dir.join("out.su2"))
        .args(["--refine-faces", "zmin", "--yplus", "1"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(stderr.contains("--yplus needs --reynolds"), "{stderr}");
    assert!(!dir.join("out.su2").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
