//! The one runner of described labs. A lab is a [`Recipe`]: its [`LabInfo`] (keys as data
//! included), its parameters, and a `build` function that returns its [`Scene`] (usually a
//! [`Shaded`] scene: a [`Stage`] plus [`Pass`]es, whose uniform blocks are filled from the
//! parameters by GLSL name). [`Runner`] implements [`Lab`] for every recipe: parameters, keys,
//! reload, programs (so the GLSL-versus-WGSL round trip reaches every lab) and the title.

use super::{params_title, Input, Lab, BuildContext, LabInfo};
use crate::error::Result;
use crate::gpu::Gpu;
use crate::params::{ParamSpec, Params};
use crate::render::{
    AnyProgram, Bind, BindingKind, Computed, Faces, Frame, GpuMesh, Load, ParamBlock, Program, RenderState, VertexType,
};

/// A lab as data.
pub struct Recipe {
    /// Name, title, size, keys, files.
    pub info: LabInfo,
    /// Its parameters, in groups (a stage's, then the effect's).
    pub params: &'static [&'static [ParamSpec]],
    /// Whether a clock drives `time` in a window.
    pub animated: bool,
    /// The window title, when not [`params_title`].
    pub title: Option<fn(&LabInfo, &Params) -> String>,
    /// Builds the scene for the parameters at their defaults.
    pub build: fn(&BuildContext, &Params) -> Result<Box<dyn Scene>>,
}

impl Recipe {
    /// The parameters at their defaults.
    pub fn params(&self) -> Params {
        let mut p = Params::new(&[]);
        for group in self.params {
            p.extend(group);
        }
        p
    }
}

/// The list entry of a described lab (`labs::register!` makes one per recipe).
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
/// input its rows do not (a stage's mouse and object keys).
pub trait Scene {
    /// Input no key row took; returns whether anything changed.
    fn input(&mut self, _p: &mut Params, _input: Input) -> bool {
        false
    }
    /// Its programs.
    fn programs(&mut self) -> Vec<&mut dyn AnyProgram>;
    /// Records one frame.
    fn render(&mut self, p: &Params, frame: &mut Frame<'_>) -> Result<()>;
    /// What the window title adds after the recipe's: state that is no parameter (a fly
    /// camera that left its start); empty for most scenes.
    fn status(&self, _p: &Params) -> String {
        String::new()
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
        let scene = (recipe.build)(cx, &params)?;
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
        let title = match self.recipe.title {
            Some(title) => title(&self.recipe.info, &self.params),
            None => params_title(&self.recipe.info, &self.params),
        };
        title + &self.scene.status(&self.params)
    }
}

/// Where a [`Shaded`] scene's camera and geometry come from.
pub trait Stage: 'static {
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
    /// The faces to draw this frame ([`Faces`]); `None` leaves the passes' own.
    fn faces(&self, _p: &Params) -> Option<Faces> {
        None
    }
    /// Writes its blocks for a `width` × `height` frame and returns the mesh to draw.
    fn prepare(&mut self, gpu: &Gpu, p: &Params, width: u32, height: u32) -> &GpuMesh<Self::Vertex>;
    /// Its part of the window title ([`Scene::status`]).
    fn status(&self, _p: &Params) -> String {
        String::new()
    }
}

/// A fixed mesh and no matrices (2D labs drawn in clip space).
pub struct Flat<V: VertexType>(pub GpuMesh<V>);

impl<V: VertexType + 'static> Stage for Flat<V> {
    type Vertex = V;
    fn prepare(&mut self, _gpu: &Gpu, _p: &Params, _width: u32, _height: u32) -> &GpuMesh<V> {
        &self.0
    }
}

/// A shader pair and its fixed-function state.
#[derive(Clone, Copy, Debug)]
pub struct Pass {
    /// Vertex shader file.
    pub vert: &'static str,
    /// Fragment shader file.
    pub frag: &'static str,
    /// Its state.
    pub state: RenderState,
    /// Its name in labels and messages (`flat`); empty: its number.
    pub name: &'static str,
}

impl Pass {
    /// `vert` + `frag` with GL's state and the depth test.
    pub const fn new(vert: &'static str, frag: &'static str) -> Pass {
        Pass {
            vert,
            frag,
            state: RenderState::GL,
            name: "",
        }
    }

    /// With a name for labels and messages.
    pub const fn named(self, name: &'static str) -> Pass {
        Pass { name, ..self }
    }

    /// With another state.
    pub const fn state(self, state: RenderState) -> Pass {
        Pass { state, ..self }
    }
}

/// Which passes a frame draws.
#[derive(Clone, Copy, Debug)]
pub enum Draw {
    /// Every pass, in order.
    All,
    /// The pass the choice parameter names (`shading`: flat, Gouraud, Phong).
    Pick(&'static str),
}

/// Values a lab computes per frame for its uniform blocks.
pub type Hook = fn(&Params, &mut Computed);

/// What a [`Shaded`] scene draws: passes, which of them, the per-frame hook and the clear
/// colour.
pub struct Look {
    /// The passes.
    pub passes: &'static [Pass],
    /// Which to draw.
    pub draw: Draw,
    /// Values computed per frame (`None`: every member is a parameter).
    pub hook: Option<Hook>,
    /// `glClearColor`.
    pub clear: [f64; 3],
}

impl Look {
    /// Every pass drawn in order on black, every block member a parameter.
    pub const fn new(passes: &'static [Pass]) -> Look {
        Look {
            passes,
            draw: Draw::All,
            hook: None,
            clear: [0.0; 3],
        }
    }

    /// With values computed per frame.
    pub const fn hook(self, hook: Hook) -> Look {
        Look {
            hook: Some(hook),
            ..self
        }
    }

    /// Drawing only the pass the choice `param` names.
    pub const fn pick(self, param: &'static str) -> Look {
        Look {
            draw: Draw::Pick(param),
            ..self
        }
    }
}

/// A stage drawn by passes whose uniform blocks are the stage's, the lab's own resources
/// (textures) or, for every other block, a [`ParamBlock`] filled by name.
pub struct Shaded<S: Stage> {
    label: String,
    stage: S,
    look: &'static Look,
    programs: Vec<Program<S::Vertex>>,
    blocks: Vec<ParamBlock>,
    computed: Computed,
}

impl<S: Stage> Shaded<S> {
    /// Compiles the passes and binds them: the stage's blocks, `own` resources, and a
    /// [`ParamBlock`] for every other uniform block the shaders declare.
    pub fn build(
        cx: &BuildContext,
        name: &str,
        p: &Params,
        stage: S,
        look: &'static Look,
        own: Vec<Bind>,
    ) -> Result<Box<dyn Scene>> {
        let mut computed = Computed::default();
        if let Some(hook) = look.hook {
            hook(p, &mut computed);
        }
        let mut programs = Vec::new();
        let mut blocks: Vec<ParamBlock> = Vec::new();
        let mut given = stage.binds();
        given.extend(own);
        for (i, pass) in look.passes.iter().enumerate() {
            let label = match (look.passes.len(), pass.name) {
                (1, _) => name.to_owned(),
                (_, "") => format!("{name}.{i}"),
                (_, pass) => format!("{name}.{pass}"),
            };
            let mut program = Program::new(cx, &label, pass.vert, pass.frag, pass.state)?;
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
                        &computed,
                    )?);
                }
                binds.extend(blocks.iter().filter(|k| k.name() == b.name).map(ParamBlock::bind));
            }
            program.bind(cx.gpu, binds)?;
            programs.push(program);
        }
        Ok(Box::new(Shaded {
            label: name.to_owned(),
            stage,
            look,
            programs,
            blocks,
            computed,
        }))
    }
}

impl<S: Stage> Scene for Shaded<S> {
    fn input(&mut self, p: &mut Params, input: Input) -> bool {
        self.stage.input(p, input)
    }
    fn programs(&mut self) -> Vec<&mut dyn AnyProgram> {
        self.programs.iter_mut().map(|p| p as &mut dyn AnyProgram).collect()
    }
    fn status(&self, p: &Params) -> String {
        self.stage.status(p)
    }
    fn render(&mut self, p: &Params, frame: &mut Frame<'_>) -> Result<()> {
        if let Some(hook) = self.look.hook {
            hook(p, &mut self.computed);
        }
        for block in &mut self.blocks {
            block.fill(p, &self.computed)?;
            block.upload(frame.gpu);
        }
        let which = match self.look.draw {
            Draw::All => 0..self.programs.len(),
            Draw::Pick(choice) => {
                let i = p.index_of(choice).min(self.programs.len() - 1);
                i..i + 1
            }
        };
        if let Some(faces) = self.stage.faces(p) {
            for program in &mut self.programs[which.clone()] {
                program.set_faces(frame.gpu, faces)?;
            }
        }
        let mesh = self.stage.prepare(frame.gpu, p, frame.width, frame.height);
        let [r, g, b] = self.look.clear;
        let mut pass = frame.pass(&self.label, Load::Clear([r, g, b]));
        for program in &self.programs[which] {
            program.draw(&mut pass, mesh);
        }
        Ok(())
    }
}
