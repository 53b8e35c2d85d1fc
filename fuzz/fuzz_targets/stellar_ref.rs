//! Feeds arbitrary bytes to the Stellar reference readers (`.tri`, `.ts`, `.sierp`, `.hex`; the
//! first byte picks the format): each must return Ok or Err, never panic, hang or exhaust memory.
#![no_main]
use libfuzzer_sys::fuzz_target;
use starplex::io::{stellar_ref, Format, ReadOptions};

fuzz_target!(|data: &[u8]| {
    let Some((&sel, text)) = data.split_first() else {
        return;
    };
    let format = [Format::Tri, Format::Ts, Format::Sierp, Format::Hex][(sel % 4) as usize];
    let name = format!("fuzz.{}", format.extension());
    let _ = stellar_ref::read_from(text, name.as_ref(), format, &ReadOptions::default());
});
