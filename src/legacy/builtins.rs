//! GL 2.0's built-in names and what each becomes in GLSL 450.

use naga::ShaderStage;

/// A member of the built-in state block (`sl_GlState`, binding 0), filled from the scene and
/// the `gl_*` parameters.
#[derive(Debug, PartialEq, Eq)]
pub struct StateMember {
    /// Its GLSL name (GL's).
    pub name: &'static str,
    /// Its declaration inside the block.
    pub decl: &'static str,
    /// The structs it needs, declared before the block.
    pub structs: &'static [&'static str],
}

const fn member(name: &'static str, decl: &'static str, structs: &'static [&'static str]) -> StateMember {
    StateMember { name, decl, structs }
}

/// The built-in structs, by name.
pub const STRUCTS: &[(&str, &str)] = &[
    (
        "gl_LightSourceParameters",
        "struct gl_LightSourceParameters { vec4 ambient; vec4 diffuse; vec4 specular; vec4 position; \
         vec4 halfVector; vec3 spotDirection; float spotExponent; float spotCutoff; float spotCosCutoff; \
         float constantAttenuation; float linearAttenuation; float quadraticAttenuation; };",
    ),
    (
        "gl_MaterialParameters",
        "struct gl_MaterialParameters { vec4 emission; vec4 ambient; vec4 diffuse; vec4 specular; float shininess; };",
    ),
    (
        "gl_LightModelParameters",
        "struct gl_LightModelParameters { vec4 ambient; };",
    ),
    (
        "gl_LightModelProducts",
        "struct gl_LightModelProducts { vec4 sceneColor; };",
    ),
    (
        "gl_LightProducts",
        "struct gl_LightProducts { vec4 ambient; vec4 diffuse; vec4 specular; };",
    ),
    (
        "gl_DepthRangeParameters",
        "struct gl_DepthRangeParameters { float near; float far; float diff; };",
    ),
];

/// Every built-in uniform that the state block can hold, in block order.
pub const STATE: &[StateMember] = &[
    member("gl_ModelViewMatrix", "mat4 gl_ModelViewMatrix;", &[]),
    member("gl_ProjectionMatrix", "mat4 gl_ProjectionMatrix;", &[]),
    member(
        "gl_ModelViewProjectionMatrix",
        "mat4 gl_ModelViewProjectionMatrix;",
        &[],
    ),
    member("gl_ModelViewMatrixInverse", "mat4 gl_ModelViewMatrixInverse;", &[]),
    member("gl_ProjectionMatrixInverse", "mat4 gl_ProjectionMatrixInverse;", &[]),
    member(
        "gl_ModelViewProjectionMatrixInverse",
        "mat4 gl_ModelViewProjectionMatrixInverse;",
        &[],
    ),
    member("gl_ModelViewMatrixTranspose", "mat4 gl_ModelViewMatrixTranspose;", &[]),
    member(
        "gl_ProjectionMatrixTranspose",
        "mat4 gl_ProjectionMatrixTranspose;",
        &[],
    ),
    member(
        "gl_ModelViewProjectionMatrixTranspose",
        "mat4 gl_ModelViewProjectionMatrixTranspose;",
        &[],
    ),
    member(
        "gl_ModelViewMatrixInverseTranspose",
        "mat4 gl_ModelViewMatrixInverseTranspose;",
        &[],
    ),
    member(
        "gl_ProjectionMatrixInverseTranspose",
        "mat4 gl_ProjectionMatrixInverseTranspose;",
        &[],
    ),
    member(
        "gl_ModelViewProjectionMatrixInverseTranspose",
        "mat4 gl_ModelViewProjectionMatrixInverseTranspose;",
        &[],
    ),
    member("gl_NormalMatrix", "mat3 gl_NormalMatrix;", &[]),
    member("gl_Color", "vec4 gl_Color;", &[]),
    member(
        "gl_DepthRange",
        "gl_DepthRangeParameters gl_DepthRange;",
        &["gl_DepthRangeParameters"],
    ),
    member(
        "gl_LightSource",
        "gl_LightSourceParameters gl_LightSource[8];",
        &["gl_LightSourceParameters"],
    ),
    member(
        "gl_LightModel",
        "gl_LightModelParameters gl_LightModel;",
        &["gl_LightModelParameters"],
    ),
    member(
        "gl_FrontMaterial",
        "gl_MaterialParameters gl_FrontMaterial;",
        &["gl_MaterialParameters"],
    ),
    member(
        "gl_FrontLightModelProduct",
        "gl_LightModelProducts gl_FrontLightModelProduct;",
        &["gl_LightModelProducts"],
    ),
    member(
        "gl_FrontLightProduct",
        "gl_LightProducts gl_FrontLightProduct[8];",
        &["gl_LightProducts"],
    ),
];

/// GL's limits as Mesa reports them, for the `gl_Max*` constants a shader may use.
pub const MAX_LIGHTS: usize = 8;
/// `gl_MaxTextureCoords`.
pub const MAX_TEXTURE_COORDS: u32 = 8;

/// What a `gl_*` name becomes.
#[derive(Debug, PartialEq, Eq)]
pub enum Builtin {
    /// A member of the state block.
    State(&'static StateMember),
    /// `gl_Vertex`: the mesh position, w = 1.
    Vertex,
    /// `gl_Normal`: the mesh normal.
    Normal,
    /// `gl_MultiTexCoord0`: the mesh's texture coordinates (the teapot's; 0 elsewhere).
    MultiTexCoord0,
    /// `gl_MultiTexCoord1`..`7`: GL's current texture coordinates, (0, 0, 0, 1).
    MultiTexCoordN,
    /// `gl_FrontColor` (vertex output).
    FrontColor,
    /// `gl_Color` in a fragment shader: the interpolated `gl_FrontColor`.
    ColorIn,
    /// `gl_TexCoord[i]` (both stages).
    TexCoord,
    /// `gl_FragColor`.
    FragColor,
    /// `gl_FragData[0]`.
    FragData,
    /// A built-in GLSL 450 has too (`gl_Position`, `gl_FragCoord`, ...).
    Native,
    /// A constant (`gl_MaxLights`), replaced by its value.
    Constant(&'static str),
    /// Not supported: why.
    Unsupported(&'static str),
    /// Not a name of this stage: why.
    WrongStage(&'static str),
}

/// What `name` is in `stage` (None: not a GL built-in; naga decides).
pub fn classify(name: &str, stage: ShaderStage) -> Option<Builtin> {
    let vertex = stage == ShaderStage::Vertex;
    if name == "gl_Color" {
        return Some(if vertex {
            Builtin::State(state_member("gl_Color")?)
        } else {
            Builtin::ColorIn
        });
    }
    if let Some(member) = state_member(name) {
        return Some(Builtin::State(member));
    }
    let only_vertex = |b: Builtin| {
        if vertex {
            b
        } else {
            Builtin::WrongStage("is a vertex shader built-in")
        }
    };
    let only_fragment = |b: Builtin| {
        if vertex {
            Builtin::WrongStage("is a fragment shader built-in")
        } else {
            b
        }
    };
    Some(match name {
        "gl_Vertex" => only_vertex(Builtin::Vertex),
        "gl_Normal" => only_vertex(Builtin::Normal),
        "gl_MultiTexCoord0" => only_vertex(Builtin::MultiTexCoord0),
        "gl_MultiTexCoord1" | "gl_MultiTexCoord2" | "gl_MultiTexCoord3" | "gl_MultiTexCoord4" | "gl_MultiTexCoord5"
        | "gl_MultiTexCoord6" | "gl_MultiTexCoord7" => only_vertex(Builtin::MultiTexCoordN),
        "gl_FrontColor" => only_vertex(Builtin::FrontColor),
        "gl_TexCoord" => Builtin::TexCoord,
        "gl_FragColor" => only_fragment(Builtin::FragColor),
        "gl_FragData" => only_fragment(Builtin::FragData),
        "gl_Position" | "gl_PointSize" => only_vertex(Builtin::Native),
        "gl_FragCoord" | "gl_FrontFacing" | "gl_FragDepth" | "gl_PointCoord" => only_fragment(Builtin::Native),
        "gl_MaxLights" => Builtin::Constant("8"),
        "gl_MaxTextureCoords" => Builtin::Constant("8"),
        "gl_MaxDrawBuffers" => Builtin::Constant("8"),
        "gl_ClipVertex" | "gl_ClipPlane" | "gl_MaxClipPlanes" => {
            Builtin::Unsupported("user clip planes (gl_ClipVertex, gl_ClipPlane) are not supported")
        }
        "gl_FogCoord" | "gl_FogFragCoord" | "gl_Fog" => Builtin::Unsupported("fixed-function fog is not supported"),
        "gl_SecondaryColor" | "gl_FrontSecondaryColor" | "gl_BackSecondaryColor" => {
            Builtin::Unsupported("the secondary colour is not supported")
        }
        "gl_BackColor" | "gl_BackMaterial" | "gl_BackLightProduct" | "gl_BackLightModelProduct" => {
            Builtin::Unsupported("two-sided lighting state (back colour and material) is not supported")
        }
        "gl_TextureMatrix"
        | "gl_TextureMatrixInverse"
        | "gl_TextureMatrixTranspose"
        | "gl_TextureMatrixInverseTranspose" => Builtin::Unsupported("texture matrices are not supported"),
        "gl_Point" => Builtin::Unsupported("point parameters (gl_Point) are not supported"),
        "gl_TextureEnvColor" | "gl_EyePlaneS" | "gl_EyePlaneT" | "gl_EyePlaneR" | "gl_EyePlaneQ"
        | "gl_ObjectPlaneS" | "gl_ObjectPlaneT" | "gl_ObjectPlaneR" | "gl_ObjectPlaneQ" => {
            Builtin::Unsupported("fixed-function texturing state is not supported")
        }
        _ if name.starts_with("gl_Max") => Builtin::Unsupported("this implementation limit is not supported"),
        _ => return None,
    })
}

fn state_member(name: &str) -> Option<&'static StateMember> {
    STATE.iter().find(|m| m.name == name)
}

/// What a texture lookup of GLSL 1.10 becomes: (GLSL 450 function, sampler dimension), or why
/// it is not supported.
pub fn texture_function(name: &str) -> Option<Result<(&'static str, SamplerDim), &'static str>> {
    Some(match name {
        "texture2D" => Ok(("texture", SamplerDim::D2)),
        "texture2DProj" => Ok(("textureProj", SamplerDim::D2)),
        "texture2DLod" => Ok(("textureLod", SamplerDim::D2)),
        "texture2DProjLod" => Ok(("textureProjLod", SamplerDim::D2)),
        "textureCube" => Ok(("texture", SamplerDim::Cube)),
        "textureCubeLod" => Ok(("textureLod", SamplerDim::Cube)),
        "texture1D" | "texture1DProj" | "texture1DLod" | "texture1DProjLod" => {
            Err("1D textures are not supported (sampler2D and samplerCube are)")
        }
        "texture3D" | "texture3DProj" | "texture3DLod" | "texture3DProjLod" => {
            Err("3D textures are not supported (sampler2D and samplerCube are)")
        }
        "shadow1D" | "shadow2D" | "shadow1DProj" | "shadow2DProj" | "shadow1DLod" | "shadow2DLod"
        | "shadow1DProjLod" | "shadow2DProjLod" => Err("shadow samplers are not supported"),
        "noise1" | "noise2" | "noise3" | "noise4" => {
            Err("the built-in noise functions are not supported (most GL drivers return 0)")
        }
        _ => return None,
    })
}

/// A sampler's dimension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SamplerDim {
    /// `sampler2D`.
    D2,
    /// `samplerCube`.
    Cube,
}

impl SamplerDim {
    /// The GLSL 1.10 type name.
    pub fn legacy_name(self) -> &'static str {
        match self {
            SamplerDim::D2 => "sampler2D",
            SamplerDim::Cube => "samplerCube",
        }
    }

    /// The GLSL 450 texture type.
    pub fn texture_type(self) -> &'static str {
        match self {
            SamplerDim::D2 => "texture2D",
            SamplerDim::Cube => "textureCube",
        }
    }
}

/// Built-in functions and keywords of GLSL 450 that GLSL 1.10 lets a shader use as its own
/// names (`uniform sampler2D texture;`): such names are renamed `sl_NAME` in the translation.
pub const CLASHES: &[&str] = &[
    "texture",
    "textureSize",
    "textureProj",
    "textureLod",
    "textureOffset",
    "texelFetch",
    "texelFetchOffset",
    "textureProjOffset",
    "textureLodOffset",
    "textureProjLod",
    "textureProjLodOffset",
    "textureGrad",
    "textureGradOffset",
    "textureProjGrad",
    "textureProjGradOffset",
    "textureGather",
    "textureGatherOffset",
    "textureQueryLod",
    "textureQueryLevels",
    "sinh",
    "cosh",
    "tanh",
    "asinh",
    "acosh",
    "atanh",
    "trunc",
    "round",
    "roundEven",
    "modf",
    "isnan",
    "isinf",
    "floatBitsToInt",
    "floatBitsToUint",
    "intBitsToFloat",
    "uintBitsToFloat",
    "fma",
    "frexp",
    "ldexp",
    "packUnorm2x16",
    "packSnorm2x16",
    "packUnorm4x8",
    "packSnorm4x8",
    "unpackUnorm2x16",
    "unpackSnorm2x16",
    "unpackUnorm4x8",
    "unpackSnorm4x8",
    "packHalf2x16",
    "unpackHalf2x16",
    "determinant",
    "inverse",
    "bitfieldExtract",
    "bitfieldInsert",
    "bitfieldReverse",
    "bitCount",
    "findLSB",
    "findMSB",
    "dFdxFine",
    "dFdyFine",
    "dFdxCoarse",
    "dFdyCoarse",
    "fwidthFine",
    "fwidthCoarse",
    "barrier",
];
