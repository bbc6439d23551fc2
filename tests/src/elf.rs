//! Just enough of an ELF64 little-endian file (a shared library) for the
//! tests: its sections' names and contents.

/// One section: its name and its bytes in the file.
pub struct Section<'a> {
    /// The section's name.
    pub name: String,
    /// Its bytes.
    pub data: &'a [u8],
}

fn u16_at(bytes: &[u8], o: usize) -> usize {
    u16::from_le_bytes([bytes[o], bytes[o + 1]]) as usize
}

fn u32_at(bytes: &[u8], o: usize) -> usize {
    u32::from_le_bytes([bytes[o], bytes[o + 1], bytes[o + 2], bytes[o + 3]]) as usize
}

fn u64_at(bytes: &[u8], o: usize) -> usize {
    let mut b = [0u8; 8];
    b.copy_from_slice(&bytes[o..o + 8]);
    u64::from_le_bytes(b) as usize
}

/// The sections of an ELF64 little-endian file (panics on anything else).
pub fn sections(bytes: &[u8]) -> Vec<Section<'_>> {
    assert_eq!(&bytes[..4], b"\x7fELF", "not an ELF file");
    assert_eq!((bytes[4], bytes[5]), (2, 1), "not ELF64 little-endian");
    let (table, entry) = (u64_at(bytes, 0x28), u16_at(bytes, 0x3A));
    let (count, names) = (u16_at(bytes, 0x3C), u16_at(bytes, 0x3E));
    let header = |k: usize| table + k * entry;
    let data = |k: usize| {
        let (offset, size) = (
            u64_at(bytes, header(k) + 0x18),
            u64_at(bytes, header(k) + 0x20),
        );
        // SHT_NOBITS (.bss) occupies no bytes in the file.
        if u32_at(bytes, header(k) + 4) == 8 {
            &bytes[0..0]
        } else {
            &bytes[offset..offset + size]
        }
    };
    let strings = data(names);
    (0..count)
        .map(|k| {
            let at = u32_at(bytes, header(k));
            let end = strings[at..].iter().position(|&b| b == 0).unwrap_or(0);
            Section {
                name: String::from_utf8_lossy(&strings[at..at + end]).into_owned(),
                data: data(k),
            }
        })
        .collect()
}

/// The highest `GLIBC_x.y` symbol version a shared library needs, as (x, y);
/// read from its dynamic string table (`.dynstr`).
pub fn highest_glibc(bytes: &[u8]) -> Option<(u32, u32)> {
    let sections = sections(bytes);
    let dynstr = sections.iter().find(|s| s.name == ".dynstr")?;
    dynstr
        .data
        .split(|&b| b == 0)
        .filter_map(|s| std::str::from_utf8(s).ok()?.strip_prefix("GLIBC_"))
        .filter_map(|v| {
            let (major, minor) = v.split_once('.')?;
            let minor = minor.split('.').next()?;
            Some((major.parse().ok()?, minor.parse().ok()?))
        })
        .max()
}
