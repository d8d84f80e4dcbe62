//! Typed arrays as base64 text (standard alphabet, padded), little-endian, as the page's
//! `Float64Array`, `Float32Array` and `Uint8/16/32Array` read them back.

use base64::engine::general_purpose::STANDARD;
use base64::Engine as _;

/// Bytes as base64 (the `base64` crate's standard engine: standard alphabet, padded).
pub fn encode(bytes: &[u8]) -> String {
    STANDARD.encode(bytes)
}

/// f64 values, little-endian, as base64.
pub fn encode_f64(values: &[f64]) -> String {
    encode_le(values, f64::to_le_bytes)
}

/// f32 values, little-endian, as base64.
pub fn encode_f32(values: &[f32]) -> String {
    encode_le(values, f32::to_le_bytes)
}

/// Values as base64 of the bytes `le` gives each, one value after the other.
fn encode_le<T: Copy, const N: usize>(values: &[T], le: fn(T) -> [u8; N]) -> String {
    encode(&values.iter().flat_map(|&v| le(v)).collect::<Vec<u8>>())
}

/// Unsigned integers in the fewest bytes that hold the largest (1, 2 or 4), little-endian:
/// `(bytes per value, base64)`.
pub fn encode_uint(values: &[u32]) -> (u8, String) {
    let max = values.iter().copied().max().unwrap_or(0);
    let width: u8 = if max <= u32::from(u8::MAX) {
        1
    } else if max <= u32::from(u16::MAX) {
        2
    } else {
        4
    };
    let bytes: Vec<u8> = values
        .iter()
        .flat_map(|v| v.to_le_bytes().into_iter().take(usize::from(width)))
        .collect();
    (width, encode(&bytes))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_vectors() {
        // RFC 4648 section 10
        let cases = [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ];
        for (plain, coded) in cases {
            assert_eq!(encode(plain.as_bytes()), coded);
        }
        assert_eq!(encode_uint(&[1, 255]), (1, encode(&[1, 255])));
        assert_eq!(encode_uint(&[1, 256]), (2, encode(&[1, 0, 0, 1])));
        assert_eq!(encode_uint(&[70_000]).0, 4);
        assert_eq!(encode_f64(&[1.0]), encode(&1.0f64.to_le_bytes()));
        assert_eq!(
            encode_f32(&[1.0, -2.5]),
            encode(&[0, 0, 128, 63, 0, 0, 32, 192])
        );
    }
}
