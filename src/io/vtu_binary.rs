//! Binary VTU data: VTK XML "appended" raw data, each array zlib-compressed in blocks (the
//! layout ParaView, VTK and meshio read with `header_type="UInt64"` and
//! `compressor="vtkZLibDataCompressor"`). The writer builds the arrays and compresses their
//! blocks on the threads; the reader's decoder takes either header width, compressed or not, and never
//! sizes an allocation by a count in the file.

use flate2::read::ZlibDecoder;
use glam::DVec3;
use quick_xml::escape::escape;
use rayon::prelude::*;
use std::io::{Read, Write};

/// Uncompressed bytes per block (VTK's readers take any size; a large block compresses a
/// little better, and a 10⁷-tet mesh still splits into hundreds of blocks for the threads).
pub const BLOCK: usize = 1 << 20;

/// A value type of a `DataArray`: its little-endian bytes.
pub trait Element: Copy + Send + Sync {
    fn put(self, out: &mut Vec<u8>);
}

macro_rules! little_endian {
    ($($t:ty),*) => {$(
        impl Element for $t {
            fn put(self, out: &mut Vec<u8>) {
                out.extend_from_slice(&self.to_le_bytes());
            }
        }
    )*};
}
little_endian!(f64, f32, i64, i32, u8);

/// The raw little-endian bytes of `values`.
pub fn bytes_of<T: Element>(values: impl Iterator<Item = T>, len: usize) -> Vec<u8> {
    let mut out = Vec::with_capacity(len * std::mem::size_of::<T>());
    for v in values {
        v.put(&mut out);
    }
    out
}

/// The raw little-endian bytes that `put` writes for each of `items`, built on the threads
/// (the connectivity of a large mesh is tens of megabytes).
pub fn par_bytes_of<S: Sync>(items: &[S], put: impl Fn(&S, &mut Vec<u8>) + Sync) -> Vec<u8> {
    let pieces: Vec<Vec<u8>> = items
        .par_chunks(1 << 16)
        .map(|part| {
            let mut out = Vec::new();
            for item in part {
                put(item, &mut out);
            }
            out
        })
        .collect();
    pieces.concat()
}

/// Arrays as appended data, each: the UInt64 header (blocks, block size, last block's size,
/// each block's compressed size), then the zlib blocks. The blocks of all the arrays are
/// compressed on the threads at once (a small array alone would keep one thread waiting).
pub fn encode_all(raws: &[&[u8]]) -> std::io::Result<Vec<Vec<u8>>> {
    let jobs: Vec<(usize, &[u8])> = raws
        .iter()
        .enumerate()
        .flat_map(|(a, raw)| raw.chunks(BLOCK).map(move |chunk| (a, chunk)))
        .collect();
    let blocks: Vec<(usize, Vec<u8>)> = jobs
        .into_par_iter()
        .map(|(a, chunk)| Ok((a, super::zlib_block::encode(chunk)?)))
        .collect::<std::io::Result<_>>()?;
    let mut out = Vec::with_capacity(raws.len());
    for (a, raw) in raws.iter().enumerate() {
        let mine: Vec<&Vec<u8>> = (blocks.iter())
            .filter(|(b, _)| *b == a)
            .map(|(_, z)| z)
            .collect();
        let last = match raw.len() % BLOCK {
            0 if raw.is_empty() => 0,
            0 => BLOCK,
            r => r,
        };
        let body: usize = mine.iter().map(|z| z.len()).sum();
        let mut array = Vec::with_capacity(8 * (3 + mine.len()) + body);
        for n in [mine.len(), BLOCK, last] {
            array.extend_from_slice(&(n as u64).to_le_bytes());
        }
        for z in &mine {
            array.extend_from_slice(&(z.len() as u64).to_le_bytes());
        }
        for z in &mine {
            array.extend_from_slice(z);
        }
        out.push(array);
    }
    Ok(out)
}

/// The VTK cell type of a cell of `n` nodes: line, triangle, tetrahedron (else polygon).
pub fn vtk_type(n: usize) -> u8 {
    match n {
        2 => 3,
        3 => 5,
        4 => 10,
        5 => 14,
        6 => 13,
        _ => 7,
    }
}

/// Write `points`, `cells`, integer cell data `ints` and real cell data `reals` as a VTU whose
/// arrays are appended raw data in zlib blocks (deflated, or stored where deflate would not
/// pay: `zlib_block`): the same arrays and names as the ASCII writer, in a fraction of the
/// bytes and the time. Points stay Float64 (every bit kept); indices and integer data are
/// Int32 where they fit, the real data Float32.
pub fn write_vtu<C: super::cells::CellNodes>(
    w: &mut dyn Write,
    points: &[DVec3],
    cells: &[C],
    ints: &[(String, Vec<i64>)],
    reals: &[(String, Vec<f64>)],
) -> std::io::Result<()> {
    let n = cells.len();
    let connectivity: usize = cells.iter().map(|c| c.node_count()).sum();
    let mut offsets = Vec::with_capacity(n);
    let mut end = 0i64;
    for c in cells {
        end += c.node_count() as i64;
        offsets.push(end);
    }
    // Indices as Int32 where they fit (half the bytes; every reader takes either width).
    let narrow = points.len() <= i32::MAX as usize && connectivity <= i32::MAX as usize;
    let index_type = if narrow { "Int32" } else { "Int64" };
    let put_index = |v: i64, out: &mut Vec<u8>| {
        if narrow {
            (v as i32).put(out)
        } else {
            v.put(out)
        }
    };
    let conn = par_bytes_of(cells, |c, out| {
        for v in c.nodes() {
            put_index(v as i64, out);
        }
    });
    let off = par_bytes_of(&offsets, |&v, out| put_index(v, out));
    // (XML of the array without its offset, raw bytes), in the order they are appended.
    let mut arrays: Vec<(String, String, Vec<u8>)> = vec![
        (
            "Points".into(),
            r#"type="Float64" NumberOfComponents="3""#.into(),
            par_bytes_of(points, |p, out| {
                p.to_array().into_iter().for_each(|x| x.put(out))
            }),
        ),
        (
            "Cells".into(),
            format!(r#"type="{index_type}" Name="connectivity""#),
            conn,
        ),
        (
            "Cells".into(),
            format!(r#"type="{index_type}" Name="offsets""#),
            off,
        ),
        (
            "Cells".into(),
            r#"type="UInt8" Name="types""#.into(),
            bytes_of(cells.iter().map(|c| vtk_type(c.node_count())), n),
        ),
    ];
    for (name, data) in ints {
        let fits = data.iter().all(|&v| i32::try_from(v).is_ok());
        let (ty, bytes) = if fits {
            (
                "Int32",
                bytes_of(data.iter().map(|&v| v as i32), data.len()),
            )
        } else {
            ("Int64", bytes_of(data.iter().copied(), data.len()))
        };
        let attrs = format!(r#"type="{ty}" Name="{}""#, escape(name));
        arrays.push(("CellData".into(), attrs, bytes));
    }
    // The real data are quality measures for viewing: single precision is plenty.
    for (name, data) in reals {
        arrays.push((
            "CellData".into(),
            format!(r#"type="Float32" Name="{}""#, escape(name)),
            par_bytes_of(data, |&v, out| (v as f32).put(out)),
        ));
    }
    let raws: Vec<&[u8]> = arrays.iter().map(|(_, _, raw)| &raw[..]).collect();
    let encoded = encode_all(&raws)?;
    writeln!(w, r#"<?xml version="1.0"?>"#)?;
    writeln!(
        w,
        r#"<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64" compressor="vtkZLibDataCompressor">"#
    )?;
    writeln!(w, "<UnstructuredGrid>")?;
    writeln!(
        w,
        r#"<Piece NumberOfPoints="{}" NumberOfCells="{n}">"#,
        points.len()
    )?;
    let mut offset = 0usize;
    let mut section = "";
    for ((parent, attrs, _), bytes) in arrays.iter().zip(&encoded) {
        if parent != section {
            if !section.is_empty() {
                writeln!(w, "</{section}>")?;
            }
            writeln!(w, "<{parent}>")?;
            section = parent;
        }
        writeln!(
            w,
            r#"<DataArray {attrs} format="appended" offset="{offset}"/>"#
        )?;
        offset += bytes.len();
    }
    if section == "Cells" {
        writeln!(w, "</Cells>\n<CellData>")?;
        section = "CellData";
    }
    writeln!(w, "</{section}>")?;
    writeln!(w, "</Piece></UnstructuredGrid>")?;
    write!(w, r#"<AppendedData encoding="raw">"#)?;
    write!(w, "\n_")?;
    for bytes in &encoded {
        w.write_all(bytes)?;
    }
    writeln!(w, "\n</AppendedData></VTKFile>")
}

/// How a file's appended data is laid out (its `VTKFile` attributes).
#[derive(Clone, Copy, Debug)]
pub struct Layout {
    /// `header_type="UInt64"` (else UInt32).
    pub header64: bool,
    /// `compressor="vtkZLibDataCompressor"` (else uncompressed).
    pub zlib: bool,
}

/// The bytes of the array at `offset` in the appended data `data` (what follows the `_`).
pub fn decode(data: &[u8], offset: usize, layout: Layout) -> Result<Vec<u8>, String> {
    let word = if layout.header64 { 8 } else { 4 };
    let mut at = offset;
    let mut next = |what: &str| -> Result<u64, String> {
        let b = data.get(at..at + word).ok_or_else(|| {
            format!("the appended data ends inside an array header (its {what}, at byte {at})")
        })?;
        at += word;
        Ok(if word == 8 {
            u64::from_le_bytes(b.try_into().unwrap_or_default())
        } else {
            u64::from(u32::from_le_bytes(b.try_into().unwrap_or_default()))
        })
    };
    if !layout.zlib {
        let n = next("byte count")? as usize;
        let start = offset + word;
        return data
            .get(start..start.saturating_add(n))
            .map(<[u8]>::to_vec)
            .ok_or_else(|| format!("an array of {n} bytes at offset {offset} runs past the end"));
    }
    let blocks = next("block count")?;
    let block = next("block size")?;
    let last = next("last block size")?;
    let mut sizes = Vec::new();
    for _ in 0..blocks {
        sizes.push(next("compressed block size")? as usize);
    }
    let mut out = Vec::new();
    for (i, &size) in sizes.iter().enumerate() {
        let z = data
            .get(at..at.saturating_add(size))
            .ok_or_else(|| format!("compressed block {i} at offset {offset} runs past the end"))?;
        at += size;
        let want = if i + 1 == sizes.len() && last != 0 {
            last
        } else {
            block
        };
        let before = out.len();
        ZlibDecoder::new(z)
            .take(want)
            .read_to_end(&mut out)
            .map_err(|e| format!("compressed block {i} at offset {offset}: {e}"))?;
        if (out.len() - before) as u64 != want {
            return Err(format!(
                "compressed block {i} at offset {offset} holds {} bytes, not {want}",
                out.len() - before
            ));
        }
    }
    Ok(out)
}

/// Values of VTK type `ty` from little-endian `bytes`, as f64 (exact for every integer type
/// up to 2⁵³) and, for the integer types, as i64.
pub fn numbers(bytes: &[u8], ty: &str) -> Result<Vec<Number>, String> {
    macro_rules! read {
        ($t:ty, $n:expr, $wrap:expr) => {
            bytes
                .chunks_exact($n)
                .map(|c| $wrap(<$t>::from_le_bytes(c.try_into().unwrap_or_default())))
                .collect()
        };
    }
    let size = match ty {
        "Int8" | "UInt8" => 1,
        "Int16" | "UInt16" => 2,
        "Int32" | "UInt32" | "Float32" => 4,
        "Int64" | "UInt64" | "Float64" => 8,
        other => return Err(format!("unknown DataArray type \"{other}\"")),
    };
    if !bytes.len().is_multiple_of(size) {
        return Err(format!(
            "{} bytes is not a whole number of {ty} values",
            bytes.len()
        ));
    }
    Ok(match ty {
        "Int8" => read!(i8, 1, |x| Number::Int(i64::from(x))),
        "UInt8" => read!(u8, 1, |x| Number::Int(i64::from(x))),
        "Int16" => read!(i16, 2, |x| Number::Int(i64::from(x))),
        "UInt16" => read!(u16, 2, |x| Number::Int(i64::from(x))),
        "Int32" => read!(i32, 4, |x| Number::Int(i64::from(x))),
        "UInt32" => read!(u32, 4, |x| Number::Int(i64::from(x))),
        "Int64" => read!(i64, 8, Number::Int),
        "UInt64" => read!(u64, 8, |x| i64::try_from(x)
            .map_or(Number::Real(x as f64), Number::Int)),
        "Float32" => read!(f32, 4, |x| Number::Real(f64::from(x))),
        _ => read!(f64, 8, Number::Real),
    })
}

/// A value read from binary data.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Number {
    Int(i64),
    Real(f64),
}

/// A value type the reader asks binary data for.
pub trait FromNumber: Sized {
    fn from_number(n: Number) -> Option<Self>;
}

impl FromNumber for f64 {
    fn from_number(n: Number) -> Option<Self> {
        Some(match n {
            Number::Int(i) => i as f64,
            Number::Real(x) => x,
        })
    }
}

impl FromNumber for i64 {
    fn from_number(n: Number) -> Option<Self> {
        match n {
            Number::Int(i) => Some(i),
            Number::Real(_) => None,
        }
    }
}

impl FromNumber for usize {
    fn from_number(n: Number) -> Option<Self> {
        match n {
            Number::Int(i) => usize::try_from(i).ok(),
            Number::Real(_) => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arrays_round_trip_through_zlib_blocks_of_either_header_width() {
        // Three blocks and a bit: the last block is short.
        let values: Vec<f64> = (0..(3 * BLOCK / 8 + 1000))
            .map(|i| i as f64 * 0.5)
            .collect();
        let raw = bytes_of(values.iter().copied(), values.len());
        let mut data = vec![0u8; 5];
        data.extend(encode_all(&[&raw]).unwrap().remove(0));
        let layout = Layout {
            header64: true,
            zlib: true,
        };
        assert_eq!(decode(&data, 5, layout).unwrap(), raw);
        let back = numbers(&raw, "Float64").unwrap();
        assert_eq!(back[1001], Number::Real(500.5));
        // Uncompressed, 32-bit header: a byte count and the bytes.
        let mut plain = (raw.len() as u32).to_le_bytes().to_vec();
        plain.extend_from_slice(&raw);
        let layout = Layout {
            header64: false,
            zlib: false,
        };
        assert_eq!(decode(&plain, 0, layout).unwrap(), raw);
    }

    #[test]
    fn a_truncated_or_lying_array_is_an_error_not_a_huge_allocation() {
        let raw = bytes_of([1i64, 2, 3].into_iter(), 3);
        let data = encode_all(&[&raw]).unwrap().remove(0);
        let layout = Layout {
            header64: true,
            zlib: true,
        };
        assert!(decode(&data[..data.len() - 3], 0, layout).is_err());
        // A header claiming 2⁶⁰-byte blocks: the block holds what it holds, and that is
        // reported as not the size claimed.
        let mut lying = data.clone();
        lying[8..16].copy_from_slice(&(1u64 << 60).to_le_bytes());
        lying[16..24].copy_from_slice(&0u64.to_le_bytes());
        let e = decode(&lying, 0, layout).unwrap_err();
        assert!(e.contains("not"), "{e}");
        assert!(numbers(&[0u8; 7], "Int64").is_err());
    }
}
