//! The one runner of described labs. A lab is a [`Recipe`]: its [`LabInfo`] (keys as data
//! included), its parameters, and a `build` function that returns its [`Scene`]. Most scenes
//! are a [`MaterialScene`], as in three-d: a [`Geometry`] (the camera, the matrices and the mesh:
//! the vertex stage's inputs) drawn with a [`Material`] (one or more [`ShaderPair`]s and the
//! values it [`Derive`]s each frame), whose uniform blocks are filled from the parameters by
//! GLSL name. [`Runner`] implements [`Lab`] for every recipe: parameters, keys, reload, programs
//! (so the GLSL-versus-WGSL round trip reaches every lab) and the title.

use super::{params_title, BuildContext, Input, Lab, LabInfo};
use crate::error::Result;
use crate::gpu::Gpu;
use crate::params::{ParamSpec, Params};
use crate::render::{
    AnyProgram, Bind, BindingKind, Culling, Derived, Frame, GpuMesh, Load, ParamBlock, Program, RenderState, VertexType,
};

/// A lab as data.
pub struct Recipe {
    /// Name, title, size, keys, files.
    pub info: LabInfo,
    /// Its parameters, in groups (a geometry's, then the effect's).
    pub params: &'static [&'static [ParamSpec]],
    /// Whether a clock drives `time` in a window.
    pub animated: bool,
    /// Builds the scene for the parameters at their defaults.
    pub build: fn(&BuildContext, &Params) -> Result<Box<dyn Scene>>,
}

impl Recipe {
    /// A lab that does not animate: its info, its parameters (in groups) and how its scene is
    /// built.
    pub const fn new(
        info: LabInfo,
        params: &'static [&'static [ParamSpec]],
        build: fn(&BuildContext, &Params) -> Result<Box<dyn Scene>>,
    ) -> Recipe {
        Recipe {
            info,
            params,
            animated: false,
            build,
        }
    }

    /// With a clock driving its `time` in a window (Space pauses it).
    pub const fn animated(self) -> Recipe {
        Recipe { animated: true, ..self }
    }

    /// The parameters at their defaults.
    pub fn params(&self) -> Params {
        let mut p = Params::new(&[]);
        for group in self.params {
            p.extend(group);
        }
        p
    }
}

/// The list entry of a described lab (`course::register!` makes one per recipe).
#[macro_export]
macro_rules! entry {
    ($recipe:path) => {
        $crate::lab::LabEntry {
            info: &$recipe.info,
            params: || $recipe.params(),
            new: |cx| $crate::lab::Runner::boxed(cx, &$recipe),
        }
    };
}

/// What a recipe's scene does: draw for the parameters, hand out its programs, and take the
/// input its rows do not (a geometry's mouse and object keys).
pub trait Scene: wgpu::WasmNotSend {
    /// Input no key row took; returns whether anything changed.
    fn input(&mut self, _p: &mut Params, _input: Input) -> bool {
        false
    }
    /// Its programs.
    fn programs(&mut self) -> Vec<&mut dyn AnyProgram>;
    /// Records one frame.
    fn render(&mut self, p: &Params, frame: &mut Frame<'_>) -> Result<()>;
    /// The window title: the original's and the parameters away from their defaults
    /// ([`params_title`]) unless the scene says more (a fly camera that left its start).
    fn title(&self, info: &LabInfo, p: &Params) -> String {
        params_title(info, p)
    }
}

/// Drives a [`Recipe`].
pub struct Runner {
    recipe: &'static Recipe,
    params: Params,
    scene: Box<dyn Scene>,
}

impl Runner {
    /// Builds the recipe's lab.
    pub fn boxed(cx: &BuildContext, recipe: &'static Recipe) -> Result<Box<dyn Lab>> {
        let params = recipe.params();
        let cx = cx.named(recipe.info.name);
        let scene = (recipe.build)(&cx, &params)?;
        Ok(Box::new(Runner { recipe, params, scene }))
    }
}

impl Lab for Runner {
    fn info(&self) -> &'static LabInfo {
        &self.recipe.info
    }
    fn params(&self) -> &Params {
        &self.params
    }
    fn params_mut(&mut self) -> &mut Params {
        &mut self.params
    }
    fn input(&mut self, input: Input) -> bool {
        self.recipe.info.keys.apply(&mut self.params, input) || self.scene.input(&mut self.params, input)
    }
    fn reload(&mut self, cx: &BuildContext) -> Result<()> {
        for program in self.scene.programs() {
            program.reload(cx)?;
        }
        Ok(())
    }
    fn render(&mut self, frame: &mut Frame<'_>) -> Result<()> {
        self.scene.render(&self.params, frame)
    }
    fn programs(&mut self) -> Vec<&mut dyn AnyProgram> {
        self.scene.programs()
    }
    fn animated(&self) -> bool {
        self.recipe.animated
    }
    fn title(&self) -> String {
        self.scene.title(&self.recipe.info, &self.params)
    }
}

/// What a [`MaterialScene`] draws: the camera, the matrices and the mesh (the vertex stage's
/// inputs), with their keys and mouse.
pub trait Geometry: wgpu::WasmNotSend + 'static {
    /// The vertices it draws.
    type Vertex: VertexType;
    /// Its keys and mouse; returns whether anything changed.
    fn input(&mut self, _p: &mut Params, _input: Input) -> bool {
        false
    }
    /// The uniform blocks it fills (its matrices).
    fn binds(&self) -> Vec<Bind> {
        Vec::new()
    }
    /// How the faces are culled this frame ([`Culling`]); `None` leaves the pairs' own.
    fn culling(&self, _p: &Params) -> Option<Culling> {
        None
    }
    /// Writes its blocks for a `width` × `height` frame and returns the mesh to draw.
    fn prepare(&mut self, gpu: &Gpu, p: &Params, width: u32, height: u32) -> &GpuMesh<Self::Vertex>;
    /// The window title ([`Scene::title`]).
    fn title(&self, info: &LabInfo, p: &Params) -> String {
        params_title(info, p)
    }
}

/// A shader pair and its fixed-function state.
#[derive(Clone, Copy, Debug)]
pub struct ShaderPair {
    /// Vertex shader file.
    pub vert: &'static str,
    /// Fragment shader file.
    pub frag: &'static str,
    /// Its state.
    pub state: RenderState,
    /// Its name in labels and messages (`flat`); empty: its number.
    pub name: &'static str,
}

impl ShaderPair {
    /// `vert` + `frag` with GL's state and the depth test.
    pub const fn new(vert: &'static str, frag: &'static str) -> ShaderPair {
        ShaderPair {
            vert,
            frag,
            state: RenderState::GL,
            name: "",
        }
    }

    /// With a name for labels and messages.
    pub const fn named(self, name: &'static str) -> ShaderPair {
        ShaderPair { name, ..self }
    }

    /// With another state.
    pub const fn state(self, state: RenderState) -> ShaderPair {
        ShaderPair { state, ..self }
    }
}

/// Which of a material's shader pairs a frame draws.
#[derive(Clone, Copy, Debug)]
pub enum PairChoice {
    /// Every pair, in order.
    All,
    /// The pair the choice parameter names (`shading`: flat, Gouraud, Phong).
    ChosenBy(&'static str),
}

/// Values a material derives from the parameters each frame for its uniform blocks (a time
/// wrapped to its period, a light in eye space).
pub type Derive = fn(&Params, &mut Derived);

/// How a [`MaterialScene`] shades its geometry (three-d's and Bevy's material): its shader
/// pairs, which of them a frame draws, the values it derives each frame, and the clear colour.
pub struct Material {
    /// The shader pairs.
    pub pairs: &'static [ShaderPair],
    /// Which to draw.
    pub choice: PairChoice,
    /// Values derived per frame (`None`: every member is a parameter).
    pub derive: Option<Derive>,
    /// `glClearColor`.
    pub clear: [f64; 3],
}

impl Material {
    /// Every pair drawn in order on black, every block member a parameter.
    pub const fn new(pairs: &'static [ShaderPair]) -> Material {
        Material {
            pairs,
            choice: PairChoice::All,
            derive: None,
            clear: [0.0; 3],
        }
    }

    /// With values derived per frame.
    pub const fn derive(self, derive: Derive) -> Material {
        Material {
            derive: Some(derive),
            ..self
        }
    }

    /// Drawing only the pair the choice `param` names.
    pub const fn chosen_by(self, param: &'static str) -> Material {
        Material {
            choice: PairChoice::ChosenBy(param),
            ..self
        }
    }
}

/// A [`Geometry`] drawn with a [`Material`] (three-d's `Gm`): the material's uniform blocks are
/// the geometry's, the lab's own resources (textures) or, for every other block, a
/// [`ParamBlock`] filled from the parameters by name.
pub struct MaterialScene<G: Geometry> {
    label: &'static str,
    geometry: G,
    material: &'static Material,
    programs: Vec<Program<G::Vertex>>,
    blocks: Vec<ParamBlock>,
    derived: Derived,
}

impl<G: Geometry> MaterialScene<G> {
    /// Compiles the material's pairs and binds them: the geometry's blocks, and a
    /// [`ParamBlock`] for every other uniform block the shaders declare.
    pub fn build(cx: &BuildContext, p: &Params, geometry: G, material: &'static Material) -> Result<Box<dyn Scene>> {
        Self::build_with(cx, p, geometry, material, Vec::new())
    }

    /// [`MaterialScene::build`] with the lab's own resources (`own`: textures, samplers,
    /// blocks it fills itself) bound by name too.
    pub fn build_with(
        cx: &BuildContext,
        p: &Params,
        geometry: G,
        material: &'static Material,
        own: Vec<Bind>,
    ) -> Result<Box<dyn Scene>> {
        let name = cx.name;
        let mut derived = Derived::default();
        if let Some(derive) = material.derive {
            derive(p, &mut derived);
        }
        let mut programs = Vec::new();
        let mut blocks: Vec<ParamBlock> = Vec::new();
        let mut given = geometry.binds();
        given.extend(own);
        for (i, pair) in material.pairs.iter().enumerate() {
            let label = match (material.pairs.len(), pair.name) {
                (1, _) => name.to_owned(),
                (_, "") => format!("{name}.{i}"),
                (_, pair) => format!("{name}.{pair}"),
            };
            let mut program = Program::new(cx, &label, pair.vert, pair.frag, pair.state)?;
            let mut binds = Vec::new();
            for b in program.bindings() {
                if let Some(g) = given.iter().find(|g| g.name == b.name) {
                    binds.push(g.clone());
                    continue;
                }
                // A texture or sampler the lab does not provide is left out: `Program::bind`
                // names it, as for any program.
                let BindingKind::Uniform(layout) = &b.kind else {
                    continue;
                };
                if !blocks.iter().any(|k| k.name() == b.name) {
                    blocks.push(ParamBlock::new(
                        cx.gpu,
                        &format!("{name}.{}", b.name),
                        layout,
                        p,
                        &derived,
                    )?);
                }
                binds.extend(blocks.iter().filter(|k| k.name() == b.name).map(ParamBlock::bind));
            }
            program.bind(cx.gpu, binds)?;
            programs.push(program);
        }
        Ok(Box::new(MaterialScene {
            label: name,
            geometry,
            material,
            programs,
            blocks,
            derived,
        }))
    }
}

impl<G: Geometry> Scene for MaterialScene<G> {
    fn input(&mut self, p: &mut Params, input: Input) -> bool {
        self.geometry.input(p, input)
    }
    fn programs(&mut self) -> Vec<&mut dyn AnyProgram> {
        self.programs.iter_mut().map(|p| p as &mut dyn AnyProgram).collect()
    }
    fn title(&self, info: &LabInfo, p: &Params) -> String {
        self.geometry.title(info, p)
    }
    fn render(&mut self, p: &Params, frame: &mut Frame<'_>) -> Result<()> {
        if let Some(derive) = self.material.derive {
            derive(p, &mut self.derived);
        }
        for block in &mut self.blocks {
            block.fill(p, &self.derived)?;
            block.upload(frame.gpu);
        }
        let which = match self.material.choice {
            PairChoice::All => 0..self.programs.len(),
            PairChoice::ChosenBy(choice) => {
                let i = p.index_of(choice).min(self.programs.len() - 1);
                i..i + 1
            }
        };
        if let Some(culling) = self.geometry.culling(p) {
            for program in &mut self.programs[which.clone()] {
                program.set_culling(frame.gpu, culling)?;
            }
        }
        let mesh = self.geometry.prepare(frame.gpu, p, frame.width, frame.height);
        let [r, g, b] = self.material.clear;
        let mut pass = frame.pass(self.label, Load::Clear([r, g, b]));
        for program in &self.programs[which] {
            program.draw(&mut pass, mesh);
        }
        Ok(())
    }
}
