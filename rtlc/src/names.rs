//! Signal names and match labels as rust-hdl's Verilog generator reads them
//! (`ident_fixup` in rust-hdl-core's `verilog_gen.rs`): loop variables replaced by
//! their value, `.`/`::` turned into `$`, a trailing `$next` dropped, and array
//! indices (`up_sync[i]`) evaluated into `$0`, `$1`... (with `evalexpr`, as rust-hdl).

use crate::error::{Error, Result};

/// The loop variables in scope: (name, value), innermost last.
pub type Loops = [(String, usize)];

/// rust-hdl's identifier normalisation.
pub fn fixup(raw: &str, loops: &Loops) -> Result<String> {
    let mut x = raw.to_owned();
    for (var, val) in loops {
        if &x == var {
            x = val.to_string();
        }
    }
    if x.starts_with('.') {
        x.remove(0);
    }
    x = x.replace('.', "$").replace("::", "$").trim_end_matches("$next").to_owned();
    while let Some(open) = x.find('[') {
        let close = x[open..].find(']').map(|c| c + open).ok_or_else(|| Error::Unsupported(format!("unbalanced index in `{raw}`")))?;
        let inner = &x[open + 1..close];
        let v = eval_index(inner, loops).map_err(|e| Error::Unsupported(format!("index `{inner}` in `{raw}`: {e}")))?;
        x = format!("{}${}{}", &x[..open], v, &x[close + 1..]);
    }
    Ok(x)
}

fn eval_index(text: &str, loops: &Loops) -> std::result::Result<i64, String> {
    use evalexpr::ContextWithMutableVariables;
    let mut ctx = evalexpr::HashMapContext::new();
    for (var, val) in loops {
        ctx.set_value(var.clone(), (*val as i64).into()).map_err(|e| e.to_string())?;
    }
    match evalexpr::eval_with_context(text, &ctx).map_err(|e| e.to_string())? {
        evalexpr::Value::Int(i) if i >= 0 => Ok(i),
        v => Err(format!("evaluates to {v:?}, not an index")),
    }
}

/// A Rust integer literal as `hdl_gen` quotes it (`3`, `0x1F`, `0b1_0`, `7u8`).
pub fn parse_int(text: &str) -> Option<u128> {
    let t: String = text.chars().filter(|c| *c != '_').collect();
    let t = t.trim();
    let (radix, digits) = if let Some(r) = t.strip_prefix("0x") {
        (16, r)
    } else if let Some(r) = t.strip_prefix("0b") {
        (2, r)
    } else if let Some(r) = t.strip_prefix("0o") {
        (8, r)
    } else {
        (10, t)
    };
    let end = digits.find(|c: char| !c.is_digit(radix)).unwrap_or(digits.len());
    let (num, suffix) = digits.split_at(end);
    if num.is_empty() {
        return None;
    }
    const SUFFIXES: [&str; 13] = ["", "u8", "u16", "u32", "u64", "u128", "usize", "i8", "i16", "i32", "i64", "i128", "isize"];
    if !SUFFIXES.contains(&suffix) {
        return None;
    }
    u128::from_str_radix(num, radix).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fixup_like_rust_hdl() {
        let loops = vec![("i".to_string(), 2usize), ("j".to_string(), 5usize)];
        assert_eq!(fixup("up_sync[i]$clock$next", &loops).unwrap(), "up_sync$2$clock");
        assert_eq!(fixup("rx[i]", &loops).unwrap(), "rx$2");
        assert_eq!(fixup("a[(i+1)]$b[j]", &loops).unwrap(), "a$3$b$5");
        assert_eq!(fixup("i", &loops).unwrap(), "2");
        assert_eq!(fixup("Field$Idle", &loops).unwrap(), "Field$Idle");
        assert_eq!(fixup("Field::Idle", &loops).unwrap(), "Field$Idle");
        assert_eq!(fixup("x$next", &[]).unwrap(), "x");
        assert!(fixup("rx[k]", &loops).is_err());
    }

    #[test]
    fn int_literals() {
        assert_eq!(parse_int("3"), Some(3));
        assert_eq!(parse_int("0x1F"), Some(31));
        assert_eq!(parse_int("0b1_01"), Some(5));
        assert_eq!(parse_int("7u8"), Some(7));
        assert_eq!(parse_int("12usize"), Some(12));
        assert_eq!(parse_int("x"), None);
        assert_eq!(parse_int("3q"), None);
    }
}
