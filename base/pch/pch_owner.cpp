// The object that owns a product precompiled header (product_pch.cmake); no code.
