//! Creating the wgpu device: the adapter the environment asks for
//! (`WGPU_BACKEND`, `WGPU_ADAPTER_NAME`, `WGPU_POWER_PREF`), the optional
//! features the lab uses when the adapter has them, and the adapter's real
//! limits (the shadow map may be as large as the device allows).

use thiserror::Error;

/// What to install when no adapter exists.
pub const INSTALL_HINT: &str = "on Debian/Ubuntu install Mesa's software Vulkan driver: \
apt-get install -y mesa-vulkan-drivers libvulkan1 (or set WGPU_BACKEND=gl for llvmpipe)";

#[derive(Debug, Error)]
pub enum GpuError {
    #[error("no GPU adapter found for backends {backends}; {INSTALL_HINT}")]
    NoAdapter { backends: String },
    #[error("WGPU_ADAPTER_NAME='{0}' matches no adapter (found: {1})")]
    NoNamedAdapter(String, String),
    #[error("the GPU adapter '{adapter}' refused to create a device: {source}")]
    Device {
        adapter: String,
        source: wgpu::RequestDeviceError,
    },
}

/// An adapter with its device and queue.
pub struct GpuContext {
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
}

/// Optional features the lab uses when present: GPU timings and filtered
/// 32-bit float moment maps.
pub const OPTIONAL_FEATURES: wgpu::Features =
    wgpu::Features::TIMESTAMP_QUERY.union(wgpu::Features::FLOAT32_FILTERABLE);

/// The device the lab asks for on `adapter`: the optional features it has and
/// its own limits. The app gives eframe the same descriptor.
pub fn device_descriptor(adapter: &wgpu::Adapter) -> wgpu::DeviceDescriptor<'static> {
    wgpu::DeviceDescriptor {
        label: Some("lumlab device"),
        required_features: adapter.features() & OPTIONAL_FEATURES,
        required_limits: adapter.limits(),
        ..Default::default()
    }
}

/// One line naming the adapter and its backend.
pub fn describe_adapter(adapter: &wgpu::Adapter) -> String {
    let info = adapter.get_info();
    format!(
        "{} ({:?}, {:?}, driver {} {})",
        info.name, info.backend, info.device_type, info.driver, info.driver_info
    )
    .replace("  ", " ")
}

/// The instance as the environment configures it (`WGPU_BACKEND` etc.).
pub fn instance() -> wgpu::Instance {
    wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env())
}

/// Picks the adapter: the one `WGPU_ADAPTER_NAME` names, else wgpu's choice
/// for `WGPU_POWER_PREF` (high performance by default).
pub fn pick_adapter(instance: &wgpu::Instance) -> Result<wgpu::Adapter, GpuError> {
    if let Ok(wanted) = std::env::var("WGPU_ADAPTER_NAME") {
        let adapters = pollster::block_on(instance.enumerate_adapters(wgpu::Backends::all()));
        let names: Vec<String> = adapters.iter().map(|a| a.get_info().name).collect();
        return adapters
            .into_iter()
            .find(|a| a.get_info().name.to_lowercase().contains(&wanted.to_lowercase()))
            .ok_or_else(|| GpuError::NoNamedAdapter(wanted, names.join(", ")));
    }
    let options = wgpu::RequestAdapterOptions {
        power_preference: wgpu::PowerPreference::from_env().unwrap_or(wgpu::PowerPreference::HighPerformance),
        ..Default::default()
    };
    pollster::block_on(instance.request_adapter(&options)).map_err(|_| GpuError::NoAdapter {
        backends: format!(
            "{:?}",
            wgpu::Backends::from_env().unwrap_or(wgpu::Backends::all())
        ),
    })
}

impl GpuContext {
    /// A device with no window: for the command line, the report and tests.
    pub fn headless() -> Result<Self, GpuError> {
        let adapter = pick_adapter(&instance())?;
        let (device, queue) = pollster::block_on(adapter.request_device(&device_descriptor(&adapter)))
            .map_err(|source| GpuError::Device {
                adapter: adapter.get_info().name,
                source,
            })?;
        Ok(Self {
            adapter,
            device,
            queue,
        })
    }

    pub fn describe(&self) -> String {
        describe_adapter(&self.adapter)
    }
}

/// The Mesa variable that names `GL_ARB_color_buffer_float` to wgpu.
pub const MESA_EXTENSION_OVERRIDE: &str = "MESA_EXTENSION_OVERRIDE";
const COLOR_BUFFER_FLOAT: &str = "GL_ARB_color_buffer_float";

/// The value of [`MESA_EXTENSION_OVERRIDE`] that lets wgpu's GL back end
/// render to Rgba32Float on Mesa, given its value now; None when it already
/// names the extension.
///
/// Rendering to float targets is core since OpenGL 3.0, but wgpu-hal 30
/// takes it from the extension strings alone, and Mesa's core profile
/// (llvmpipe's GL 4.5) lists `GL_ARB_color_buffer_float` only in the
/// compatibility profile: without it the camera pass falls back to f16
/// targets (radiance above 65 504 overflows, a ΔE step is 0.002, moment
/// maps lose their precision). Other drivers ignore the variable.
pub fn mesa_extension_override(current: Option<&str>) -> Option<String> {
    let current = current.unwrap_or("").trim();
    let named = current
        .split_whitespace()
        .any(|e| e.trim_start_matches(['+', '-']) == COLOR_BUFFER_FLOAT);
    match (named, current.is_empty()) {
        (true, _) => None,
        (false, true) => Some(format!("+{COLOR_BUFFER_FLOAT}")),
        (false, false) => Some(format!("{current} +{COLOR_BUFFER_FLOAT}")),
    }
}

#[cfg(test)]
mod tests {
    use super::mesa_extension_override;

    #[test]
    fn the_override_adds_the_extension_once_and_keeps_the_user_s() {
        assert_eq!(
            mesa_extension_override(None).as_deref(),
            Some("+GL_ARB_color_buffer_float")
        );
        assert_eq!(
            mesa_extension_override(Some("-GL_EXT_foo")).as_deref(),
            Some("-GL_EXT_foo +GL_ARB_color_buffer_float")
        );
        // The user's own choice, on or off, stands.
        assert_eq!(mesa_extension_override(Some("-GL_ARB_color_buffer_float")), None);
        assert_eq!(mesa_extension_override(Some("+GL_ARB_color_buffer_float")), None);
    }
}
