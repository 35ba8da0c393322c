//! Buffers made of memory the program already has (Vulkan's `VK_EXT_external_memory_host`),
//! for the window's shared-memory presenter: lavapipe copies a frame straight into the segment
//! the X server reads, instead of into a readback buffer the presenter then copies again
//! (920 KB a frame at 640x360, ~12 % of a cheap frame's time in `perf`).
//!
//! wgpu has no API for host memory, so this goes through its hal layer: the device is opened
//! with the extension added ([`open_device`]), and a buffer is made with raw Vulkan calls and
//! handed to wgpu ([`import`]), which then owns and destroys it like any other buffer. Written
//! by hand because no kept crate does it; every Vulkan result is checked and undone on failure.

use ash::vk;
use wgpu::hal::api::Vulkan;

/// The device of `adapter`, opened as `desc` asks plus `VK_EXT_external_memory_host`; `None`
/// where that cannot be (not a CPU Vulkan adapter, or no such extension), so that the caller
/// opens it the usual way.
pub(crate) fn open_device(
    adapter: &wgpu::Adapter,
    desc: &wgpu::DeviceDescriptor<'_>,
) -> Option<Result<(wgpu::Device, wgpu::Queue), String>> {
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
    let opened = match opened {
        Ok(opened) => opened,
        Err(e) => return Some(Err(format!("opening the device with {name:?}: {e}"))),
    };
    // SAFETY: `opened` was created from this adapter's hal adapter, with `desc`'s features.
    Some(unsafe { adapter.create_device_from_hal(opened, desc) }.map_err(|e| e.to_string()))
}

/// The alignment Vulkan asks of imported host memory (its address and its size).
pub(crate) fn alignment(device: &wgpu::Device) -> Option<usize> {
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

/// A buffer (`COPY_DST`, `size` bytes) whose memory is the `size` bytes at `ptr`, on a device
/// from [`open_device`].
///
/// # Safety
/// `ptr` must stay mapped, and be used by nothing else while the GPU writes it, until the
/// returned buffer is dropped and every submission that used it has finished; `ptr` and `size`
/// must be multiples of [`alignment`].
pub(crate) unsafe fn import(
    device: &wgpu::Device,
    ptr: *mut u8,
    size: usize,
    label: &str,
) -> Result<wgpu::Buffer, String> {
    let bytes = size as u64;
    let handle = vk::ExternalMemoryHandleTypeFlags::HOST_ALLOCATION_EXT;
    let hal_buffer = {
        // SAFETY: raw calls on this device's own handles; what is made is undone on each failure.
        let hal = unsafe { device.as_hal::<Vulkan>() }.ok_or("not a Vulkan device")?;
        let raw = hal.raw_device();
        let instance = hal.shared_instance().raw_instance();
        let ext = ash::ext::external_memory_host::Device::new(instance, raw);
        let mut host = vk::MemoryHostPointerPropertiesEXT::default();
        let r =
            unsafe { (ext.fp().get_memory_host_pointer_properties_ext)(raw.handle(), handle, ptr.cast(), &mut host) };
        if r != vk::Result::SUCCESS {
            return Err(format!("vkGetMemoryHostPointerPropertiesEXT: {r}"));
        }
        let mut external = vk::ExternalMemoryBufferCreateInfo::default().handle_types(handle);
        let info = vk::BufferCreateInfo::default()
            .size(bytes)
            .usage(vk::BufferUsageFlags::TRANSFER_DST)
            .sharing_mode(vk::SharingMode::EXCLUSIVE)
            .push_next(&mut external);
        let buffer = unsafe { raw.create_buffer(&info, None) }.map_err(|e| format!("vkCreateBuffer: {e}"))?;
        let needs = unsafe { raw.get_buffer_memory_requirements(buffer) };
        let types = needs.memory_type_bits & host.memory_type_bits;
        if types == 0 || needs.size > bytes {
            unsafe { raw.destroy_buffer(buffer, None) };
            return Err(format!(
                "no memory type fits (buffer wants {} bytes of types {:#x}, the host memory offers types {:#x})",
                needs.size, needs.memory_type_bits, host.memory_type_bits
            ));
        }
        let mut import = vk::ImportMemoryHostPointerInfoEXT::default()
            .handle_type(handle)
            .host_pointer(ptr.cast());
        let alloc = vk::MemoryAllocateInfo::default()
            .allocation_size(bytes)
            .memory_type_index(types.trailing_zeros())
            .push_next(&mut import);
        let memory = match unsafe { raw.allocate_memory(&alloc, None) } {
            Ok(memory) => memory,
            Err(e) => {
                unsafe { raw.destroy_buffer(buffer, None) };
                return Err(format!("vkAllocateMemory (host pointer): {e}"));
            }
        };
        if let Err(e) = unsafe { raw.bind_buffer_memory(buffer, memory, 0) } {
            unsafe {
                raw.free_memory(memory, None);
                raw.destroy_buffer(buffer, None);
            }
            return Err(format!("vkBindBufferMemory: {e}"));
        }
        // SAFETY: the buffer is bound to the whole of `memory`; wgpu destroys both on drop
        // (freeing imported memory leaves the host memory as it is).
        unsafe { wgpu::hal::vulkan::Buffer::from_raw_managed(buffer, memory, 0, bytes) }
    };
    // SAFETY: made on this device with the usage and size the descriptor states.
    Ok(unsafe {
        device.create_buffer_from_hal::<Vulkan>(
            hal_buffer,
            &wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage: wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            },
        )
    })
}
