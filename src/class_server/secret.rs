//! The server's secrets, from the operating system's randomness (getrandom): the teacher token
//! (128 bits, hex), a student's resume secret, the session id, and the six-character join code
//! from an alphabet without look-alikes; and a comparison of secrets in constant time.

use super::ServerError;

/// The join code's alphabet: no 0/O, 1/I/L (31 characters).
pub(crate) const CODE_ALPHABET: &[u8] = b"ABCDEFGHJKMNPQRSTUVWXYZ23456789";
/// The join code's length (31^6: about 887 million codes).
pub(crate) const CODE_LENGTH: usize = 6;
/// Random bytes of a teacher token and a resume secret (128 bits).
pub(crate) const SECRET_BYTES: usize = 16;

/// `bytes` random bytes as lower-case hex.
pub(crate) fn random_hex(bytes: usize) -> Result<String, ServerError> {
    let mut buf = vec![0u8; bytes];
    getrandom::fill(&mut buf).map_err(|e| ServerError::Random {
        reason: e.to_string(),
    })?;
    Ok(buf.iter().map(|b| format!("{b:02x}")).collect())
}

/// A random u64 (an exercise's seed).
pub(crate) fn random_u64() -> Result<u64, ServerError> {
    getrandom::u64().map_err(|e| ServerError::Random {
        reason: e.to_string(),
    })
}

/// A join code: [`CODE_LENGTH`] characters of [`CODE_ALPHABET`], each uniform.
pub(crate) fn join_code() -> Result<String, ServerError> {
    let n = CODE_ALPHABET.len();
    // The largest multiple of n in a byte: bytes at or above it are drawn again.
    let limit = (256 / n * n) as u8;
    let mut code = String::with_capacity(CODE_LENGTH);
    while code.len() < CODE_LENGTH {
        let mut buf = [0u8; 16];
        getrandom::fill(&mut buf).map_err(|e| ServerError::Random {
            reason: e.to_string(),
        })?;
        for b in buf.into_iter().filter(|b| *b < limit) {
            if code.len() < CODE_LENGTH {
                code.push(CODE_ALPHABET[b as usize % n] as char);
            }
        }
    }
    Ok(code)
}

/// Whether two secrets are equal, in a time that does not depend on where they differ.
pub(crate) fn same_secret(a: &str, b: &str) -> bool {
    let (a, b) = (a.as_bytes(), b.as_bytes());
    if a.len() != b.len() {
        return false;
    }
    a.iter().zip(b).fold(0u8, |acc, (x, y)| acc | (x ^ y)) == 0
}

/// A join code as typed: trimmed, upper case.
pub(crate) fn normalized_code(code: &str) -> String {
    code.trim().to_ascii_uppercase()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_join_code_has_six_characters_of_the_alphabet() {
        for _ in 0..100 {
            let code = join_code().unwrap();
            assert_eq!(code.len(), CODE_LENGTH);
            assert!(code.bytes().all(|c| CODE_ALPHABET.contains(&c)), "{code}");
        }
    }

    #[test]
    fn a_token_is_128_bits_of_hex_and_tokens_differ() {
        let a = random_hex(SECRET_BYTES).unwrap();
        let b = random_hex(SECRET_BYTES).unwrap();
        assert_eq!(a.len(), 32);
        assert!(a.bytes().all(|c| c.is_ascii_hexdigit()));
        assert_ne!(a, b);
        assert!(same_secret(&a, &a.clone()) && !same_secret(&a, &b) && !same_secret(&a, "x"));
    }
}
