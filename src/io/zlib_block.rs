//! One block of binary VTU data as a zlib stream: deflated when that pays, else in deflate's
//! stored blocks. Coordinates and real-valued data shrink by a few percent under deflate at
//! the cost of as much time as the connectivity; storing them keeps the file readable by any
//! zlib reader (the format has one compressor per file) at memory speed.

use flate2::{Compress, Compression, FlushCompress};

/// The probe: a block whose first bytes deflate to more than this fraction of their size is
/// stored.
const PROBE_KEEPS: f64 = 0.8;
const PROBE_BYTES: usize = 1 << 16;

/// `chunk` as one zlib stream (header, deflate data, Adler-32).
pub fn encode(chunk: &[u8]) -> std::io::Result<Vec<u8>> {
    let probe = &chunk[..chunk.len().min(PROBE_BYTES)];
    if probe.len() < chunk.len()
        && (deflated(probe)?.len() as f64) > PROBE_KEEPS * probe.len() as f64
    {
        return Ok(stored(chunk));
    }
    deflated(chunk)
}

/// Deflate at the fastest level.
fn deflated(chunk: &[u8]) -> std::io::Result<Vec<u8>> {
    let mut c = Compress::new(Compression::fast(), true);
    // Deflate never grows data by more than 5 bytes per 16 KiB stored block, plus the
    // zlib header and checksum.
    let mut out = Vec::with_capacity(chunk.len() + chunk.len() / 1024 + 64);
    c.compress_vec(chunk, &mut out, FlushCompress::Finish)
        .map_err(std::io::Error::other)?;
    if c.total_in() as usize != chunk.len() {
        return Err(std::io::Error::other(
            "zlib stopped before the end of a block",
        ));
    }
    Ok(out)
}

/// The largest stored block deflate allows.
const STORED_MAX: usize = u16::MAX as usize;

/// `chunk` in stored (uncompressed) deflate blocks (RFC 1950 and 1951): header 0x78 0x01,
/// then per piece of at most 65,535 bytes a byte with the final-block bit, its length and the
/// length's complement, the bytes; then the Adler-32 of the whole, big-endian.
fn stored(chunk: &[u8]) -> Vec<u8> {
    let pieces = chunk.len().div_ceil(STORED_MAX).max(1);
    let mut out = Vec::with_capacity(chunk.len() + 5 * pieces + 6);
    out.extend_from_slice(&[0x78, 0x01]);
    let mut rest = chunk;
    loop {
        let (piece, tail) = rest.split_at(rest.len().min(STORED_MAX));
        let len = piece.len() as u16;
        out.push(u8::from(tail.is_empty()));
        out.extend_from_slice(&len.to_le_bytes());
        out.extend_from_slice(&(!len).to_le_bytes());
        out.extend_from_slice(piece);
        if tail.is_empty() {
            break;
        }
        rest = tail;
    }
    out.extend_from_slice(&adler2::adler32_slice(chunk).to_be_bytes());
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use flate2::read::ZlibDecoder;
    use std::io::Read;

    fn inflate(z: &[u8]) -> Vec<u8> {
        let mut out = Vec::new();
        ZlibDecoder::new(z).read_to_end(&mut out).unwrap();
        out
    }

    #[test]
    fn noise_is_stored_and_a_pattern_deflated_and_both_inflate_back() {
        // Pseudo-random bytes do not shrink: stored, 5 bytes per 64 KiB piece over the data.
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let noise: Vec<u8> = (0..300_000)
            .map(|_| {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                x as u8
            })
            .collect();
        let z = encode(&noise).unwrap();
        assert_eq!(z.len(), 2 + 5 * 5 + noise.len() + 4);
        assert_eq!(inflate(&z), noise);
        // A repeating pattern shrinks a lot: deflated.
        let pattern: Vec<u8> = (0..300_000u32).map(|i| (i % 7) as u8).collect();
        let z = encode(&pattern).unwrap();
        assert!(z.len() < pattern.len() / 50, "{} bytes", z.len());
        assert_eq!(inflate(&z), pattern);
        // The edges: nothing, and exactly one full stored piece.
        assert_eq!(inflate(&stored(&[])), Vec::<u8>::new());
        assert_eq!(inflate(&stored(&noise[..STORED_MAX])), &noise[..STORED_MAX]);
    }
}
