program ddc2d
end program ddc2d
