//! Files the user names on the command line for a lab to draw instead of its built-in data
//! (`--model FILE.obj`, `--texture [NAME=]FILE`, positional `FILES...` of the labs that take
//! them), read and checked before a GPU is opened.

use std::path::{Path, PathBuf};

use crate::error::Result;
use crate::images::{load_image, Image};
use crate::mesh::obj::{load_obj, ObjModel};

/// Files named on the command line (`--model`, `--texture`), already read and checked, for the
/// labs that draw a model or a picture texture; the shell refuses a flag the lab has no use for
/// ([`crate::lab::LabInfo::files`]) before reading its file. Every file is read by
/// [`crate::fsutil::read_user_file`]'s rule: a regular file within a size cap
/// ([`crate::mesh::obj::MAX_OBJ_BYTES`], [`crate::images::MAX_IMAGE_FILE_BYTES`]).
#[derive(Clone, Debug, Default)]
pub struct UserFiles {
    /// `--model FILE.obj`: a Wavefront OBJ, parsed.
    pub model: Option<UserFile<ObjModel>>,
    /// `--texture FILE`: a PNG or BMP, decoded, its top row first (the lab decides the upload
    /// order).
    pub texture: Option<UserFile<Image>>,
    /// `--texture NAME=FILE` (repeatable): pictures for the texture called NAME in the lab's
    /// shaders, decoded like `texture`, in command-line order.
    pub named_textures: Vec<(String, UserFile<Image>)>,
    /// Positional `FILES...` of a lab that declares them ([`crate::params::FileArgs`]), e.g.
    /// a user's shaders: paths only, the lab reads them (again on live reload).
    pub inputs: Vec<PathBuf>,
}

/// A file the user named, and what was read from it.
#[derive(Clone, Debug)]
pub struct UserFile<T> {
    /// The file, for messages about what is found later (e.g. a texture too large for the GPU).
    pub path: PathBuf,
    /// Its content.
    pub data: T,
}

/// No files: every lab draws its own data (tests, the bench, labs building parts lazily).
pub static NO_FILES: UserFiles = UserFiles {
    model: None,
    texture: None,
    named_textures: Vec::new(),
    inputs: Vec::new(),
};

impl UserFiles {
    /// Reads and checks the files; errors name the file (and the line, for an OBJ).
    pub fn load(model: Option<&Path>, texture: Option<&Path>) -> Result<UserFiles> {
        fn read<T>(path: Option<&Path>, load: fn(&Path) -> Result<T>) -> Result<Option<UserFile<T>>> {
            path.map(|path| {
                load(path).map(|data| UserFile {
                    path: path.to_path_buf(),
                    data,
                })
            })
            .transpose()
        }
        Ok(UserFiles {
            model: read(model, load_obj)?,
            texture: read(texture, load_image)?,
            named_textures: Vec::new(),
            inputs: Vec::new(),
        })
    }

    /// Reads `--texture NAME=FILE` pictures (errors name the file).
    pub fn load_named_textures(&mut self, named: &[(String, PathBuf)]) -> Result<()> {
        for (name, path) in named {
            let data = load_image(path)?;
            self.named_textures.push((
                name.clone(),
                UserFile {
                    path: path.clone(),
                    data,
                },
            ));
        }
        Ok(())
    }
}
