//! Why a debugger run stopped: the interpreter's [`Failure`] (a message at a span of the
//! module it ran) and the replay's [`ReplayError`] (a message, and in which shader). A leaf of
//! `debug`, so that the interpreter, the maths, the capture and the replay import it one way.

use std::sync::Arc;

use crate::shader::CompiledShader;

/// Why a run stopped without a result.
#[derive(Clone, Debug, PartialEq)]
pub struct Failure {
    /// What went wrong, in words.
    pub message: String,
    /// Where in the module's source.
    pub span: naga::Span,
}

/// Why a replay stopped: the message, and where in which shader when it is the shader's.
#[derive(Clone, Debug)]
pub struct ReplayError {
    /// What went wrong.
    pub message: String,
    /// The shader and span, if a shader's operation.
    pub at: Option<(Arc<CompiledShader>, naga::Span)>,
}
