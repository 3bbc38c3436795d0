//! [`Error`], [`Status`] and the conversion of C status codes into them.

use std::ffi::{c_char, CStr};
use std::fmt;

use progsim_sys as sys;

/// Why a call failed: the failure values of the C `ps_status` (`PS_OK` is the `Ok` of a
/// [`Result`]). The values are stable across library versions; a newer library may add
/// some, which arrive as [`Status::Unknown`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Status {
    /// `PS_ERROR_INVALID_ARGUMENT`: a parameter is NaN, out of range or nonsense (also: an
    /// unknown parameter name, a string with a NUL byte).
    InvalidArgument,
    /// `PS_ERROR_INVALID_MESH`: a mesh fails validation; the message names the first bad
    /// element.
    InvalidMesh,
    /// `PS_ERROR_INVALID_SCENE`: a scene description is malformed (typo, missing field); the
    /// message names the JSON path.
    InvalidScene,
    /// `PS_ERROR_IO`: a file cannot be read or written.
    Io,
    /// `PS_ERROR_NUMERICAL`: the solver failed (non-finite values, factorization).
    Numerical,
    /// `PS_ERROR_WRONG_CALL_ORDER`: the call needs another call first.
    WrongCallOrder,
    /// `PS_ERROR_OUT_OF_RANGE`: a level, handle or index does not exist.
    OutOfRange,
    /// `PS_ERROR_CANCELLED`: the progress callback asked to stop.
    Cancelled,
    /// `PS_ERROR_INTERSECTING`: a configuration intersects itself or another body.
    Intersecting,
    /// `PS_ERROR_INTERNAL`: a bug in progsim; please report the message.
    Internal,
    /// `PS_ERROR_NULL_ARGUMENT`: a required pointer was NULL (a bug in this binding if seen).
    NullArgument,
    /// `PS_ERROR_BUFFER_TOO_SMALL`: an output buffer was too small (a bug in this binding if
    /// seen).
    BufferTooSmall,
    /// `PS_ERROR_UNINITIALIZED_DEF`: a def-struct was not filled by its `*_def_init()` (a bug
    /// in this binding if seen).
    UninitializedDef,
    /// `PS_ERROR_VERSION_MISMATCH`: the loaded library cannot serve this binding's header
    /// version.
    VersionMismatch,
    /// `PS_ERROR_OUT_OF_MEMORY`: an allocation failed.
    OutOfMemory,
    /// `PS_ERROR_UNSUPPORTED`: a valid request that this library version cannot do yet
    /// (e.g. multi-level hierarchies).
    Unsupported,
    /// A failure code this binding does not know (from a newer library), as returned.
    Unknown(i32),
}

/// Each known status with its C value, taken from the generated bindings so the two cannot
/// disagree.
const STATUS_CODES: [(Status, sys::ps_status); 16] = [
    (Status::InvalidArgument, sys::PS_ERROR_INVALID_ARGUMENT),
    (Status::InvalidMesh, sys::PS_ERROR_INVALID_MESH),
    (Status::InvalidScene, sys::PS_ERROR_INVALID_SCENE),
    (Status::Io, sys::PS_ERROR_IO),
    (Status::Numerical, sys::PS_ERROR_NUMERICAL),
    (Status::WrongCallOrder, sys::PS_ERROR_WRONG_CALL_ORDER),
    (Status::OutOfRange, sys::PS_ERROR_OUT_OF_RANGE),
    (Status::Cancelled, sys::PS_ERROR_CANCELLED),
    (Status::Intersecting, sys::PS_ERROR_INTERSECTING),
    (Status::Internal, sys::PS_ERROR_INTERNAL),
    (Status::NullArgument, sys::PS_ERROR_NULL_ARGUMENT),
    (Status::BufferTooSmall, sys::PS_ERROR_BUFFER_TOO_SMALL),
    (Status::UninitializedDef, sys::PS_ERROR_UNINITIALIZED_DEF),
    (Status::VersionMismatch, sys::PS_ERROR_VERSION_MISMATCH),
    (Status::OutOfMemory, sys::PS_ERROR_OUT_OF_MEMORY),
    (Status::Unsupported, sys::PS_ERROR_UNSUPPORTED),
];

impl Status {
    /// The status of a C return value: `None` for `PS_OK` (0), else the failure it names.
    pub fn from_raw(code: i32) -> Option<Status> {
        if code == sys::PS_OK as i32 {
            return None;
        }
        let known = STATUS_CODES.iter().find(|(_, raw)| *raw as i32 == code);
        Some(known.map_or(Status::Unknown(code), |(status, _)| *status))
    }

    /// The C `ps_status` value of this status.
    pub fn to_raw(self) -> i32 {
        match self {
            Status::Unknown(code) => code,
            known => STATUS_CODES
                .iter()
                .find(|(status, _)| *status == known)
                .map(|(_, raw)| *raw as i32)
                .expect("every named Status is in STATUS_CODES"),
        }
    }

    /// The library's stable short name, e.g. `"PS_ERROR_INVALID_MESH"`
    /// (`"PS_ERROR_UNKNOWN_STATUS"` for a code it does not know either).
    pub fn name(self) -> &'static str {
        // SAFETY: ps_status_name() accepts any value and returns a static NUL-terminated
        // ASCII string (or NULL, handled by static_str).
        unsafe { static_str(sys::ps_status_name(self.to_raw())) }
    }
}

impl fmt::Display for Status {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A failed progsim call: what kind of failure ([`Status`]) and the library's message,
/// which starts with the C function's name and names the offending value (vertex, JSON key,
/// parameter, level, path).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Error {
    /// What kind of failure.
    pub code: Status,
    /// The library's explanation (or this binding's, for a problem caught before the call).
    pub message: String,
}

/// The result of every fallible progsim call.
pub type Result<T> = std::result::Result<T, Error>;

impl Error {
    /// An error with the given code and message.
    pub fn new(code: Status, message: impl Into<String>) -> Error {
        Error { code, message: message.into() }
    }

    /// The failure's status (same as the public field `code`).
    pub fn code(&self) -> Status {
        self.code
    }

    /// The failure's message (same as the public field `message`).
    pub fn message(&self) -> &str {
        &self.message
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.code.name(), self.message)
    }
}

impl std::error::Error for Error {}

/// Ok for `PS_OK`, else an [`Error`] whose message `message()` reads. `message` is called
/// only on failure and must be called before any other progsim call on the same handle or
/// thread, which would replace the message.
pub(crate) fn check(code: i32, message: impl FnOnce() -> *const c_char) -> Result<()> {
    match Status::from_raw(code) {
        None => Ok(()),
        Some(status) => {
            // SAFETY: every *_last_error() returns NULL or a NUL-terminated string that stays
            // valid until the next progsim call on that handle/thread; it is copied at once.
            let text = unsafe { owned_str(message()) };
            Err(Error::new(status, text))
        }
    }
}

/// Ok for `PS_OK`, else an error carrying the calling thread's `ps_last_error()` (calls
/// without a usable handle: creates, the version check).
pub(crate) fn check_thread(code: i32) -> Result<()> {
    // SAFETY: ps_last_error() takes nothing and is thread-local.
    check(code, || unsafe { sys::ps_last_error() })
}

/// An owned copy of a C string (NULL gives ""); invalid UTF-8 is replaced.
///
/// # Safety
/// `text` is NULL or points to a NUL-terminated string valid for this call.
pub(crate) unsafe fn owned_str(text: *const c_char) -> String {
    if text.is_null() {
        String::new()
    } else {
        CStr::from_ptr(text).to_string_lossy().into_owned()
    }
}

/// A static C string as `&str` (NULL or non-UTF-8 give "").
///
/// # Safety
/// `text` is NULL or points to a NUL-terminated string that lives for the whole program.
pub(crate) unsafe fn static_str(text: *const c_char) -> &'static str {
    if text.is_null() {
        ""
    } else {
        CStr::from_ptr(text).to_str().unwrap_or("")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn status_round_trips_through_raw_values() {
        assert_eq!(Status::from_raw(0), None);
        for (status, raw) in STATUS_CODES {
            assert_eq!(Status::from_raw(raw as i32), Some(status));
            assert_eq!(status.to_raw(), raw as i32);
            assert!(status.name().starts_with("PS_ERROR_"), "{status:?}: {}", status.name());
        }
        assert_eq!(Status::from_raw(99), Some(Status::Unknown(99)));
        assert_eq!(Status::Unknown(99).to_raw(), 99);
        assert_eq!(Status::InvalidMesh.name(), "PS_ERROR_INVALID_MESH");
    }

    #[test]
    fn error_displays_status_name_and_message() {
        let error = Error::new(Status::OutOfRange, "level 3 does not exist");
        assert_eq!(error.to_string(), "PS_ERROR_OUT_OF_RANGE: level 3 does not exist");
        let boxed: Box<dyn std::error::Error> = Box::new(error);
        assert!(boxed.to_string().contains("level 3"));
    }
}
