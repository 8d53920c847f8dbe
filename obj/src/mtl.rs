//! Material libraries: `newmtl`, `Kd`, `map_Kd`, `d` and `Tr`, and [`MtlLoader`], which
//! reads libraries and their textures from disk safely.

use std::collections::HashSet;
use std::io::Read;
use std::path::{Path, PathBuf};

use crate::image::{decode_png, ObjImage, MAX_TEXTURE_BYTES};
use crate::{err, number, ObjError, ReadNotes, Skipped};

/// A material from an MTL file.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjMaterial {
    /// The `newmtl` name.
    pub name: String,
    /// The diffuse colour `Kd`, each in 0..=1.
    pub kd: [f32; 3],
    /// The diffuse texture `map_Kd`, if any.
    pub map_kd: Option<TextureMap>,
    /// Opacity: `d`, or 1 − `Tr` (the later statement wins), in 0..=1; 1 when neither
    /// is given. zraster draws every face opaque: the converter carries it and says so.
    pub alpha: f32,
}

impl ObjMaterial {
    /// A material of this name in white, opaque, without a texture (what `newmtl`
    /// starts).
    pub fn new(name: &str) -> ObjMaterial {
        ObjMaterial {
            name: name.to_string(),
            kd: [1.0; 3],
            map_kd: None,
            alpha: 1.0,
        }
    }
}

/// A material's diffuse texture: MTL `map_Kd [options] FILE`.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct TextureMap {
    /// The image file, relative to the OBJ file's folder: the name in the MTL file
    /// taken relative to the library's folder (an absolute name as it is).
    pub path: String,
    /// `-clamp on`: coordinates outside 0..1 clamp instead of repeating (the default).
    pub clamp: bool,
}

/// Read the `newmtl`, `Kd`, `map_Kd`, `d` and `Tr` statements of an MTL file into `out`.
/// A `map_Kd` file is kept as written (there is no library folder to take it from).
pub fn parse_mtl(src: &str, out: &mut Vec<ObjMaterial>) -> Result<(), ObjError> {
    let mut notes = MtlNotes {
        skipped: &mut Vec::new(),
        other: &mut 0,
        warnings: &mut Vec::new(),
    };
    parse_mtl_noting(src, out, 0, "", &mut notes)
}

/// Where [`parse_mtl_noting`] puts what it skips or ignores.
pub(crate) struct MtlNotes<'a> {
    pub(crate) skipped: &'a mut Vec<Skipped>,
    pub(crate) other: &'a mut usize,
    pub(crate) warnings: &'a mut Vec<String>,
}

/// [`parse_mtl`] for the library `lib` (its name as the OBJ file gives it), read for
/// the `mtllib` statement on line `at`: skipped statements noted as if on that line,
/// `map_Kd` options it does not use as warnings.
pub(crate) fn parse_mtl_noting(
    src: &str,
    out: &mut Vec<ObjMaterial>,
    at: usize,
    lib: &str,
    notes: &mut MtlNotes<'_>,
) -> Result<(), ObjError> {
    let src = src.strip_prefix('\u{feff}').unwrap_or(src);
    for (i, raw) in src.lines().enumerate() {
        let line = i + 1;
        let text = raw.split('#').next().unwrap_or("");
        let mut toks = text.split_whitespace();
        match toks.next() {
            Some("newmtl") => out.push(ObjMaterial::new(toks.next().unwrap_or(""))),
            Some("Kd") => {
                let r = number(toks.next(), line, "Kd red")?;
                let g = number(toks.next(), line, "Kd green")?;
                let b = number(toks.next(), line, "Kd blue")?;
                let mat = current(out, line, "Kd")?;
                mat.kd = [r.clamp(0.0, 1.0), g.clamp(0.0, 1.0), b.clamp(0.0, 1.0)];
            }
            Some("d") => {
                let mut tok = toks.next();
                if tok == Some("-halo") {
                    tok = toks.next();
                }
                let d = number(tok, line, "d")?;
                current(out, line, "d")?.alpha = d.clamp(0.0, 1.0);
            }
            Some("Tr") => {
                let tr = number(toks.next(), line, "Tr")?;
                current(out, line, "Tr")?.alpha = 1.0 - tr.clamp(0.0, 1.0);
            }
            Some("map_Kd") => {
                let rest = text.trim_start().strip_prefix("map_Kd").unwrap_or("");
                let (file, clamp, ignored) = map_kd(rest, line)?;
                let mat = current(out, line, "map_Kd")?;
                if !ignored.is_empty() {
                    notes.warnings.push(format!(
                        "line {at}: in {lib}: line {line}: map_Kd {} ignored: {}",
                        if ignored.len() == 1 {
                            "option"
                        } else {
                            "options"
                        },
                        ignored.join(", ")
                    ));
                }
                mat.map_kd = Some(TextureMap {
                    path: beside(lib, file),
                    clamp,
                });
            }
            Some(kw) => ReadNotes::skip(notes.skipped, notes.other, kw, at),
            None => {}
        }
    }
    Ok(())
}

/// The material being defined: the last one.
fn current<'m>(
    out: &'m mut [ObjMaterial],
    line: usize,
    kw: &str,
) -> Result<&'m mut ObjMaterial, ObjError> {
    out.last_mut()
        .ok_or_else(|| err(line, format!("{kw} before any newmtl")))
}

/// `file`, named in the library `lib`, relative to the OBJ file's folder.
fn beside(lib: &str, file: &str) -> String {
    match Path::new(lib).parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir.join(file).to_string_lossy().into(),
        _ => file.to_string(),
    }
}

/// The first whitespace-separated token of `s` and what follows it.
fn token(s: &str) -> Option<(&str, &str)> {
    let s = s.trim_start();
    if s.is_empty() {
        return None;
    }
    let end = s.find(char::is_whitespace).unwrap_or(s.len());
    Some((&s[..end], &s[end..]))
}

/// A `map_Kd` statement after the keyword: the file name (the rest of the line after
/// the options, so names with spaces work), whether `-clamp on` was given, and the
/// options it does not use.
fn map_kd(mut rest: &str, line: usize) -> Result<(&str, bool, Vec<String>), ObjError> {
    let mut clamp = false;
    let mut ignored = Vec::new();
    while let Some((opt, after)) = token(rest) {
        // Arguments: at least, at most (numbers, for -o -s -t).
        let args = match opt {
            "-clamp" | "-blendu" | "-blendv" | "-cc" | "-bm" | "-boost" | "-texres"
            | "-imfchan" | "-type" => (1, 1),
            "-mm" => (2, 2),
            "-o" | "-s" | "-t" => (1, 3),
            _ => break,
        };
        rest = after;
        let mut values = Vec::new();
        for k in 0..args.1 {
            match token(rest) {
                Some((v, after)) if k < args.0 || v.parse::<f64>().is_ok() => {
                    values.push(v);
                    rest = after;
                }
                _ => break,
            }
        }
        if values.len() < args.0 {
            return Err(err(line, format!("map_Kd option {opt} without its value")));
        }
        if opt == "-clamp" {
            clamp = values.first() == Some(&"on");
        } else {
            ignored.push(opt.to_string());
        }
    }
    let file = rest.trim();
    if file.is_empty() {
        return Err(err(line, "map_Kd without a file name"));
    }
    Ok((file, clamp, ignored))
}

/// The largest material library [`MtlLoader`] reads: 16 MiB.
pub const MAX_MTL_BYTES: u64 = 16 << 20;

/// Reads the material libraries an OBJ file names, from the OBJ file's folder, for
/// [`parse_obj_with`](crate::parse_obj_with), and their textures
/// ([`load_texture`](MtlLoader::load_texture)) — safe for files from anywhere: it reads
/// only regular files (never a device such as `/dev/zero`, which never ends, or a FIFO,
/// which blocks its reader until something writes), of at most [`MAX_MTL_BYTES`] (a
/// texture [`MAX_TEXTURE_BYTES`]), and each library once (by its canonical path: a
/// library named again, under any name, reads as empty).
///
/// ```
/// let dir = std::env::temp_dir();
/// let mut mtl = zraster_obj::MtlLoader::new(&dir);
/// let model = zraster_obj::parse_obj_with("mtllib /dev/zero\n", |name| mtl.load(name))?;
/// assert_eq!(
///     model.warnings,
///     ["line 1: cannot read material library /dev/zero: not a regular file"]
/// );
/// # Ok::<(), zraster_obj::ObjError>(())
/// ```
#[derive(Debug, Clone, Default)]
pub struct MtlLoader {
    dir: PathBuf,
    seen: HashSet<PathBuf>,
}

impl MtlLoader {
    /// A loader for the libraries of an OBJ file in `dir`.
    pub fn new(dir: impl AsRef<Path>) -> MtlLoader {
        MtlLoader {
            dir: dir.as_ref().to_path_buf(),
            seen: HashSet::new(),
        }
    }

    /// The text of the library `name` (relative to the folder, or absolute); `""` for a
    /// file read before. `Err` says why it cannot be read.
    pub fn load(&mut self, name: &str) -> Result<String, String> {
        let path = self.dir.join(name);
        check_regular(&path, MAX_MTL_BYTES)?;
        let key = std::fs::canonicalize(&path).map_err(|e| e.to_string())?;
        if !self.seen.insert(key) {
            return Ok(String::new());
        }
        let bytes = read_regular(&path, MAX_MTL_BYTES)?;
        String::from_utf8(bytes).map_err(|_| "not UTF-8 text".into())
    }

    /// The texture `name` (a [`TextureMap::path`]: relative to the folder, or absolute),
    /// decoded from PNG. Each call reads the file (textures are not remembered). `Err`
    /// says why it cannot be read or decoded.
    pub fn load_texture(&mut self, name: &str) -> Result<ObjImage, String> {
        let path = self.dir.join(name);
        check_regular(&path, MAX_TEXTURE_BYTES)?;
        decode_png(&read_regular(&path, MAX_TEXTURE_BYTES)?)
    }
}

/// "larger than N MiB".
fn too_big(max: u64) -> String {
    format!("larger than {} MiB", max >> 20)
}

/// The type and size before opening: opening a FIFO for reading blocks.
fn check_regular(path: &Path, max: u64) -> Result<(), String> {
    let meta = std::fs::metadata(path).map_err(|e| e.to_string())?;
    if !meta.is_file() {
        return Err("not a regular file".into());
    }
    if meta.len() > max {
        return Err(too_big(max));
    }
    Ok(())
}

/// The bytes of a file [`check_regular`] has passed, at most `max` of them.
fn read_regular(path: &Path, max: u64) -> Result<Vec<u8>, String> {
    let file = std::fs::File::open(path).map_err(|e| e.to_string())?;
    // What was opened may not be what was looked at; and a file may grow.
    if !file.metadata().is_ok_and(|m| m.is_file()) {
        return Err("not a regular file".into());
    }
    let mut bytes = Vec::new();
    file.take(max + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| e.to_string())?;
    if bytes.len() as u64 > max {
        return Err(too_big(max));
    }
    Ok(bytes)
}
