//! Colour targets made of memory the program already has (Vulkan's
//! `VK_EXT_external_memory_host`), for the window's shared-memory presenter: lavapipe draws a
//! frame straight into the segment the X server reads, as the original's llvmpipe draws into
//! its shared-memory image, instead of into a texture that is then copied to a readback buffer
//! and copied again into the segment (two 920 KB copies a frame at 640x360).
//!
//! wgpu has no API for host memory, so this goes through its hal layer: the device is opened
//! with the extension added ([`open_device`]), and an image is made with raw Vulkan calls and
//! handed to wgpu ([`target`]), which then owns and destroys it like any other texture. Written
//! by hand because no kept crate does it; every Vulkan result is checked and undone on failure.

use ash::vk;
use wgpu::hal::api::Vulkan;

/// The device of `adapter`, opened as `desc` asks plus `VK_EXT_external_memory_host`; `None`
/// where that cannot be (not a CPU Vulkan adapter, no such extension, or opening failed), so
/// that the caller opens it the usual way.
pub(crate) fn open_device(
    adapter: &wgpu::Adapter,
    desc: &wgpu::DeviceDescriptor<'_>,
) -> Option<(wgpu::Device, wgpu::Queue)> {
    if adapter.get_info().device_type != wgpu::DeviceType::Cpu {
        return None;
    }
    let name = ash::ext::external_memory_host::NAME;
    // SAFETY: the hal adapter is this adapter's own; the callback only adds an extension the
    // physical device offers, which wgpu-hal allows (it removes and disables nothing).
    let opened = unsafe {
        let hal = adapter.as_hal::<Vulkan>()?;
        if !hal.physical_device_capabilities().supports_extension(name) {
            return None;
        }
        hal.open_with_callback(
            desc.required_features,
            &desc.required_limits,
            &desc.memory_hints,
            Some(Box::new(move |args| args.extensions.push(name))),
        )
    };
    // SAFETY: `opened` was created from this adapter's hal adapter, with `desc`'s features.
    unsafe { adapter.create_device_from_hal(opened.ok()?, desc) }.ok()
}

/// The alignment Vulkan asks of imported host memory (its address and its size).
fn alignment(device: &wgpu::Device) -> Option<usize> {
    // SAFETY: only queries the physical device behind this device.
    unsafe {
        let hal = device.as_hal::<Vulkan>()?;
        let mut host = vk::PhysicalDeviceExternalMemoryHostPropertiesEXT::default();
        let mut props = vk::PhysicalDeviceProperties2::default().push_next(&mut host);
        hal.shared_instance()
            .raw_instance()
            .get_physical_device_properties2(hal.raw_physical_device(), &mut props);
        usize::try_from(host.min_imported_host_pointer_alignment).ok()
    }
}

/// A colour target whose memory is host memory the caller provides, and where its pixels lie
/// in that memory.
pub(crate) struct HostTarget {
    /// The texture (`RENDER_ATTACHMENT`), owned by wgpu like any other.
    pub texture: wgpu::Texture,
    /// Bytes from the start of the memory to the first row.
    pub offset: u64,
    /// Bytes from one row to the next.
    pub row_pitch: u64,
}

/// A `width` x `height` colour target in `format` (only `Bgra8Unorm`), laid out in rows
/// (linear tiling) in host memory, on a device from [`open_device`]: `memory(size)` is asked for
/// `size` bytes (a multiple of [`alignment`]) and returns their address, aligned likewise.
/// Only for a CPU adapter, where a linear image is plain memory that another process can read
/// while the image stays in its attachment layout.
///
/// # Safety
/// The memory must stay mapped, and be read by nothing else while the GPU writes it, until the
/// texture is dropped and every submission that used it has finished.
pub(crate) unsafe fn target(
    device: &wgpu::Device,
    width: u32,
    height: u32,
    format: wgpu::TextureFormat,
    label: &str,
    memory: impl FnOnce(usize) -> Result<*mut u8, String>,
) -> Result<HostTarget, String> {
    if format != wgpu::TextureFormat::Bgra8Unorm {
        return Err(format!("no host-memory target in {format:?}"));
    }
    let align = alignment(device).ok_or("no alignment for host memory")?;
    let handle = vk::ExternalMemoryHandleTypeFlags::HOST_ALLOCATION_EXT;
    // SAFETY: raw calls on this device's own handles; what is made is undone on each failure.
    let hal = unsafe { device.as_hal::<Vulkan>() }.ok_or("not a Vulkan device")?;
    let raw = hal.raw_device();
    let mut external = vk::ExternalMemoryImageCreateInfo::default().handle_types(handle);
    let info = vk::ImageCreateInfo::default()
        .image_type(vk::ImageType::TYPE_2D)
        .format(vk::Format::B8G8R8A8_UNORM)
        .extent(vk::Extent3D {
            width,
            height,
            depth: 1,
        })
        .mip_levels(1)
        .array_layers(1)
        .samples(vk::SampleCountFlags::TYPE_1)
        .tiling(vk::ImageTiling::LINEAR)
        .usage(vk::ImageUsageFlags::COLOR_ATTACHMENT | vk::ImageUsageFlags::TRANSFER_SRC)
        .sharing_mode(vk::SharingMode::EXCLUSIVE)
        .initial_layout(vk::ImageLayout::UNDEFINED)
        .push_next(&mut external);
    let image = unsafe { raw.create_image(&info, None) }.map_err(|e| format!("vkCreateImage (linear): {e}"))?;
    let destroy = |e: String| {
        unsafe { raw.destroy_image(image, None) };
        Err(e)
    };
    let needs = unsafe { raw.get_image_memory_requirements(image) };
    let Some(size) = usize::try_from(needs.size)
        .ok()
        .and_then(|s| s.checked_next_multiple_of(align))
    else {
        return destroy(format!("an image of {} bytes", needs.size));
    };
    let ptr = match memory(size) {
        Ok(ptr) if (ptr as usize).is_multiple_of(align) => ptr,
        Ok(_) => return destroy(format!("host memory not aligned to {align} bytes")),
        Err(e) => return destroy(e),
    };
    let ext = ash::ext::external_memory_host::Device::new(hal.shared_instance().raw_instance(), raw);
    let mut host = vk::MemoryHostPointerPropertiesEXT::default();
    let r = unsafe { (ext.fp().get_memory_host_pointer_properties_ext)(raw.handle(), handle, ptr.cast(), &mut host) };
    if r != vk::Result::SUCCESS {
        return destroy(format!("vkGetMemoryHostPointerPropertiesEXT: {r}"));
    }
    let types = needs.memory_type_bits & host.memory_type_bits;
    if types == 0 {
        return destroy(format!(
            "no memory type fits (the image takes types {:#x}, the host memory offers {:#x})",
            needs.memory_type_bits, host.memory_type_bits
        ));
    }
    let mut import = vk::ImportMemoryHostPointerInfoEXT::default()
        .handle_type(handle)
        .host_pointer(ptr.cast());
    let alloc = vk::MemoryAllocateInfo::default()
        .allocation_size(size as u64)
        .memory_type_index(types.trailing_zeros())
        .push_next(&mut import);
    let memory = match unsafe { raw.allocate_memory(&alloc, None) } {
        Ok(memory) => memory,
        Err(e) => return destroy(format!("vkAllocateMemory (host pointer): {e}")),
    };
    if let Err(e) = unsafe { raw.bind_image_memory(image, memory, 0) } {
        unsafe { raw.free_memory(memory, None) };
        return destroy(format!("vkBindImageMemory: {e}"));
    }
    let layout = unsafe {
        raw.get_image_subresource_layout(
            image,
            vk::ImageSubresource {
                aspect_mask: vk::ImageAspectFlags::COLOR,
                mip_level: 0,
                array_layer: 0,
            },
        )
    };
    let desc = super::targets::target_descriptor(label, width, height, format, wgpu::TextureUsages::RENDER_ATTACHMENT);
    // The same texture as wgpu-hal describes it (its usage: a colour target).
    let hal_desc = wgpu::hal::TextureDescriptor {
        label: desc.label,
        size: desc.size,
        mip_level_count: desc.mip_level_count,
        sample_count: desc.sample_count,
        dimension: desc.dimension,
        format,
        usage: wgpu::TextureUses::COLOR_TARGET,
        memory_flags: wgpu::hal::MemoryFlags::empty(),
        view_formats: Vec::new(),
    };
    // SAFETY: the image was made as `hal_desc` says and is bound to all of `memory`; wgpu-hal
    // now owns both and destroys them on drop (freeing imported memory leaves the host memory
    // as it is).
    let hal_texture = unsafe {
        hal.texture_from_raw(
            image,
            &hal_desc,
            None,
            wgpu::hal::vulkan::TextureMemory::Dedicated(memory),
        )
    };
    drop(hal);
    // SAFETY: made on this device as `desc` states; it starts uninitialised.
    let texture =
        unsafe { device.create_texture_from_hal::<Vulkan>(hal_texture, &desc, wgpu::TextureUses::UNINITIALIZED) };
    Ok(HostTarget {
        texture,
        offset: layout.offset,
        row_pitch: layout.row_pitch,
    })
}
