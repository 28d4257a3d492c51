//! The GLB container (glTF 2.0 binary): a 12-byte header, then a JSON chunk and a BIN chunk, each
//! with its length and type and padded to 4 bytes (the JSON with spaces, the binary with zeros).

const MAGIC: u32 = 0x4654_6C67; // "glTF"
const VERSION: u32 = 2;
const CHUNK_JSON: u32 = 0x4E4F_534A; // "JSON"
const CHUNK_BIN: u32 = 0x004E_4942; // "BIN\0"

fn padded(mut bytes: Vec<u8>, pad: u8) -> Vec<u8> {
    while !bytes.len().is_multiple_of(4) {
        bytes.push(pad);
    }
    bytes
}

/// Packs `json` and `bin` into one GLB file.
pub fn pack(json: &str, bin: Vec<u8>) -> Vec<u8> {
    let json = padded(json.as_bytes().to_vec(), b' ');
    let bin = padded(bin, 0);
    let total = 12 + 8 + json.len() + if bin.is_empty() { 0 } else { 8 + bin.len() };
    let mut out = Vec::with_capacity(total);
    for word in [MAGIC, VERSION, total as u32, json.len() as u32, CHUNK_JSON] {
        out.extend_from_slice(&word.to_le_bytes());
    }
    out.extend_from_slice(&json);
    if !bin.is_empty() {
        out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        out.extend_from_slice(&CHUNK_BIN.to_le_bytes());
        out.extend_from_slice(&bin);
    }
    out
}

#[cfg(test)]
mod tests {
    #[test]
    fn header_and_chunks_are_aligned() {
        let glb = super::pack("{}", vec![1, 2, 3]);
        assert_eq!(&glb[0..4], b"glTF");
        assert_eq!(glb.len() % 4, 0);
        assert_eq!(u32::from_le_bytes(glb[8..12].try_into().unwrap()) as usize, glb.len());
        assert_eq!(u32::from_le_bytes(glb[12..16].try_into().unwrap()), 4); // "{}  "
        assert_eq!(&glb[20..24], b"{}  ");
        assert_eq!(&glb[28..32], b"BIN\0");
        assert_eq!(&glb[32..36], &[1, 2, 3, 0]);
    }
}
