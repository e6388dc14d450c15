//! Marker and region names as solvers see them. A name is the only identity a solver file
//! keeps (SU2 tags, Gmsh physical names, STL solids), so markers that share a name form one
//! group, and names are cleaned of the characters those formats and SU2 config files split on.

use crate::mesh::Marker;
use std::collections::HashMap;

/// `name` without whitespace, control characters or `" ' , ( ) = % ; #` (each becomes `_`);
/// `unnamed` when empty: the marker names the writers put in SU2 and the other formats.
pub fn clean_name(name: &str) -> String {
    let s: String = name
        .chars()
        .map(|c| {
            if c.is_whitespace() || c.is_control() || "\"',()=%;#".contains(c) {
                '_'
            } else {
                c
            }
        })
        .collect();
    if s.is_empty() {
        "unnamed".into()
    } else {
        s
    }
}

/// Markers grouped by cleaned name, groups in order of first appearance.
pub(crate) struct Groups {
    /// Cleaned name of each group.
    pub names: Vec<String>,
    /// Group of each marker.
    pub of: Vec<usize>,
}

pub(crate) fn groups(markers: &[Marker]) -> Groups {
    let mut index = HashMap::new();
    let mut names = Vec::new();
    let of = markers
        .iter()
        .map(|m| {
            let name = clean_name(&m.name);
            *index.entry(name.clone()).or_insert_with(|| {
                names.push(name);
                names.len() - 1
            })
        })
        .collect();
    Groups { names, of }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_cleaned_and_grouped() {
        assert_eq!(clean_name("left wing (upper)"), "left_wing__upper_");
        assert_eq!(clean_name(""), "unnamed");
        assert_eq!(clean_name("Flügel"), "Flügel");
        let m = |id, name: &str| Marker {
            id,
            name: name.into(),
        };
        let g = groups(&[m(0, "wing"), m(1, "farfield"), m(2, "wing")]);
        assert_eq!(g.names, ["wing", "farfield"]);
        assert_eq!(g.of, [0, 1, 0]);
    }
}
